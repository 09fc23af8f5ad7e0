// Validates glTF files with the Khronos glTF validator (npm gltf-validator): exit 0 when it
// reports no error, no warning and no info message, else 1 with its messages.
// Usage: node gltf_validate.mjs FILE.glb|FILE.gltf...
import { readFile } from 'node:fs/promises';
import { createRequire } from 'node:module';
import path from 'node:path';

const require = createRequire(import.meta.url);
const validator = require('gltf-validator');

let failed = false;
for (const file of process.argv.slice(2)) {
  const data = new Uint8Array(await readFile(file));
  const report = await validator.validateBytes(data, {
    uri: path.basename(file),
    maxIssues: 100,
    externalResourceFunction: () => Promise.reject(new Error('no external resources')),
  });
  const i = report.issues;
  const counts = `${i.numErrors} errors, ${i.numWarnings} warnings, ${i.numInfos} infos, ${i.numHints} hints`;
  if (i.numErrors || i.numWarnings || i.numInfos) {
    failed = true;
    console.log(`${file}: ${counts}`);
    for (const m of i.messages) console.log(`  ${m.severity} ${m.code} ${m.pointer ?? ''}: ${m.message}`);
  } else {
    const info = report.info;
    console.log(`${file}: valid glTF ${info.version} (${counts}; ${info.animationCount} animation, ` +
                `${info.totalVertexCount} vertices, ${info.totalTriangleCount} triangles)`);
  }
}
process.exit(failed ? 1 : 0);
