// Times the page of `qmotion view` in headless Chromium (viewer_bench.py runs it): the page's
// load until its kernel is ready, and `qmotion.interpolateAndSweep` on the page's own poses
// (the work an edit does: interpolate in WebAssembly, then the trajectories and the exact
// sweep evaluated on their grids and turned into three.js geometry), after warm-up runs.
// puppeteer-core comes from tests/interop/node_modules (npm ci there).
// Usage: node viewer_bench.mjs CHROMIUM PAGE.html RUNS OUT.json
import fs from "node:fs";
import { createRequire } from "node:module";
import path from "node:path";
import { fileURLToPath, pathToFileURL } from "node:url";

const here = path.dirname(fileURLToPath(import.meta.url));
const require = createRequire(path.join(here, "..", "interop", "package.json"));
const puppeteer = require("puppeteer-core");
const [chromium, pagePath, runs, outPath] = process.argv.slice(2);
const browser = await puppeteer.launch({
  executablePath: chromium,
  headless: true,
  args: ["--no-sandbox", "--use-angle=swiftshader", "--enable-unsafe-swiftshader",
         "--disable-background-networking"],
});
try {
  const page = await browser.newPage();
  await page.setViewport({ width: 1280, height: 800 });
  const errors = [];
  page.on("pageerror", (e) => errors.push(e.message));
  const start = Date.now();
  await page.goto(pathToFileURL(pagePath).href);
  await page.waitForFunction(() => window.qmotion?.ready === true, { timeout: 60000 });
  const loadMs = Date.now() - start;
  const result = await page.evaluate((n) => {
    const poses = window.qmotion.poses();
    const flat = poses.flatMap((p) => [p.t ?? NaN, ...p.position, ...p.quaternion]);
    for (let i = 0; i < 3; ++i) window.qmotion.interpolateAndSweep(flat);
    const ms = [];
    for (let i = 0; i < n; ++i) {
      const t0 = performance.now();
      const error = window.qmotion.interpolateAndSweep(flat);
      ms.push(performance.now() - t0);
      if (error) return { error };
    }
    ms.sort((a, b) => a - b);
    return { poses: poses.length, runs: n, median_ms: ms[Math.floor(n / 2)], min_ms: ms[0],
             max_ms: ms[n - 1] };
  }, Number(runs));
  fs.writeFileSync(outPath, JSON.stringify({ ...result, load_ms: loadMs, errors }));
} finally {
  await browser.close();
}
