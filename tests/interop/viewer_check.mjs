// Opens a page of `qmotion view` in headless Chromium (puppeteer-core from npm, Debian's
// chromium) from a file URL with the network cut off, and reports as JSON what viewer.py
// checks: console errors, requests that left the file, whether the canvas shows anything,
// the page's evaluations, and what its own pose controls do.
// Usage: node viewer_check.mjs CHROMIUM PAGE.html EDITS.json OUT.json [SCREENSHOT.png]
// EDITS.json: {"samples": n, "edits": [{"id": "pose-3-position-0", "value": 41.5}, ...],
// "downloads": DIR}: after the edits the page's Save buttons are clicked and their files
// land in DIR; the view buttons are clicked and the canvas dragged (the orbit), and where
// the camera looks from is reported after each.
import fs from "node:fs";
import { pathToFileURL } from "node:url";
import puppeteer from "puppeteer-core";

const [chromium, pagePath, editsPath, outPath, screenshotPath] = process.argv.slice(2);
const { samples, edits, downloads } = JSON.parse(fs.readFileSync(editsPath, "utf8"));
const browser = await puppeteer.launch({
  executablePath: chromium,
  headless: true,
  args: ["--no-sandbox", "--use-angle=swiftshader", "--enable-unsafe-swiftshader",
         "--disable-background-networking", "--host-resolver-rules=MAP * ~NOTFOUND"],
});
const report = { console_errors: [], outside_requests: [] };
try {
  const page = await browser.newPage();
  await page.setViewport({ width: 1280, height: 800 });
  page.on("console", (m) => { if (m.type() === "error") report.console_errors.push(m.text()); });
  page.on("pageerror", (e) => report.console_errors.push(`uncaught: ${e.message}`));
  await page.setRequestInterception(true);
  page.on("request", (r) => {
    const url = r.url();
    if (url.startsWith("file:") || url.startsWith("data:") || url.startsWith("blob:")) return r.continue();
    report.outside_requests.push(url);
    return r.abort();
  });
  await page.goto(pathToFileURL(pagePath).href);
  await page.waitForFunction(() => window.qmotion?.ready === true, { timeout: 30000 });

  const sample = () => page.evaluate((n) => {
    const [a, b] = window.qmotion.range();
    const out = [];
    for (let i = 0; i < n; ++i) {
      const t = i + 1 === n ? b : a + ((b - a) * i) / (n - 1);
      out.push({ t, pose: window.qmotion.evaluate(t) });
    }
    return out;
  }, samples);
  report.range = await page.evaluate(() => window.qmotion.range());
  report.method = await page.evaluate(() => window.qmotion.method);
  report.before = await sample();
  report.poses_before = await page.evaluate(() => window.qmotion.poses());

  // The moving object halfway, through the page's slider; then the canvas as the screen
  // shows it, decoded in a blank page (no help from the viewer).
  await page.$eval("#t", (s) => { s.value = String(Number(s.max) / 2); s.dispatchEvent(new Event("input")); });
  await page.evaluate(() => new Promise((done) => requestAnimationFrame(() => requestAnimationFrame(done))));
  const shot = await page.screenshot({ encoding: "base64" });
  if (screenshotPath) fs.writeFileSync(screenshotPath, Buffer.from(shot, "base64"));
  const box = await page.$eval("#scene", (c) => { const r = c.getBoundingClientRect(); return [r.x, r.y, r.width, r.height]; });
  const blank = await browser.newPage();
  report.canvas = await blank.evaluate(async (png, box) => {
    const img = new Image();
    img.src = `data:image/png;base64,${png}`;
    await img.decode();
    const c = document.createElement("canvas");
    [c.width, c.height] = [Math.floor(box[2]), Math.floor(box[3])];
    const g = c.getContext("2d");
    g.drawImage(img, -box[0], -box[1]);
    const px = g.getImageData(0, 0, c.width, c.height).data;
    let drawn = 0;
    const colours = new Set();
    for (let i = 0; i < px.length; i += 4) {
      if (px[i] < 245 || px[i + 1] < 245 || px[i + 2] < 245) ++drawn;
      colours.add((px[i] >> 4) * 256 + (px[i + 1] >> 4) * 16 + (px[i + 2] >> 4));
    }
    return { pixels: px.length / 4, drawn, colours: colours.size };
  }, shot, box);
  await blank.close();

  // Edit through the page's own inputs: select, type, leave the field.
  for (const e of edits) {
    const input = await page.$(`#${e.id}`);
    if (!input) throw new Error(`no control #${e.id}`);
    await input.focus();
    await page.keyboard.down("Control");
    await page.keyboard.press("KeyA");
    await page.keyboard.up("Control");
    await page.keyboard.press("Backspace");
    await input.type(String(e.value));
    await input.press("Tab");
    await page.waitForFunction(() => /interpolated again/.test(document.getElementById("status").textContent), { timeout: 10000 });
  }
  report.status = await page.$eval("#status", (s) => s.textContent);
  report.poses_after = await page.evaluate(() => window.qmotion.poses());
  report.after = await sample();
  report.drawn_paths = await page.evaluate(() => window.qmotion.drawnPaths());
  report.drawn_volume = await page.evaluate(() => window.qmotion.drawnVolume());

  // The Save buttons, clicked: their files, as Chromium downloads them.
  const cdp = await browser.target().createCDPSession();
  await cdp.send("Browser.setDownloadBehavior", { behavior: "allow", downloadPath: downloads });
  report.downloads = {};
  for (const [id, key] of [["save-poses", "poses"], ["save-motion", "motion"]]) {
    const before = new Set(fs.readdirSync(downloads));
    await page.click(`#${id}`);
    for (let i = 0; i < 100 && !report.downloads[key]; ++i) {
      await new Promise((done) => setTimeout(done, 100));
      const fresh = fs.readdirSync(downloads).filter((f) => !before.has(f) && f.endsWith(".json"));
      if (fresh.length) report.downloads[key] = `${downloads}/${fresh[0]}`;
    }
  }

  // The view buttons and the orbit: where the camera looks from after each.
  const camera = () => page.evaluate(() => window.qmotion.camera());
  report.views = {};
  for (const name of ["top", "front", "side", "iso"]) {
    await page.click(`#view-${name}`);
    report.views[name] = await camera();
  }
  const [x, y, w, h] = box;
  await page.mouse.move(x + w / 2, y + h / 2);
  await page.mouse.down();
  for (let i = 1; i <= 10; ++i) await page.mouse.move(x + w / 2 + 15 * i, y + h / 2 + 4 * i);
  await page.mouse.up();
  await page.evaluate(() => new Promise((done) => requestAnimationFrame(() => requestAnimationFrame(done))));
  report.orbited = await camera();
} catch (e) {
  report.failure = String(e.stack || e);
} finally {
  await browser.close();
}
fs.writeFileSync(outPath, JSON.stringify(report));
