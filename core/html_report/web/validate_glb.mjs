// node validate_glb.mjs MODULES_DIR FILE.glb...: runs the Khronos glTF validator (npm gltf-validator) on
// each file; prints one JSON line per file {file, errors, warnings, infos, hints, messages (the first
// 100)} and exits 1 when any file has an error. MODULES_DIR is the node_modules folder setup.sh filled
// (BUILD_DIR/web/...).
import fs from 'node:fs';
import path from 'node:path';
import { createRequire } from 'node:module';

const [modules, ...files] = process.argv.slice(2);
if (!modules || !files.length) {
  console.error('usage: node validate_glb.mjs NODE_MODULES_DIR FILE.glb...');
  process.exit(2);
}
const validator = createRequire(path.join(path.resolve(modules), 'noop.js'))('gltf-validator');
let failed = false;
for (const file of files) {
  const bytes = new Uint8Array(fs.readFileSync(file));
  // maxIssues 0: every issue counted. With a cap the validator stops counting at it, and a large scene's
  // infos (one unused TEXCOORD_0 per primitive: the 108-room office has 1,409) would hide any error after.
  const result = await validator.validateBytes(bytes, { maxIssues: 0, uri: path.basename(file) });
  const i = result.issues;
  failed ||= i.numErrors > 0;
  console.log(JSON.stringify({
    file, errors: i.numErrors, warnings: i.numWarnings, infos: i.numInfos, hints: i.numHints,
    messages: i.messages.slice(0, 100).map((m) => `${['error', 'warning', 'info', 'hint'][m.severity]} ${m.code} ${m.pointer || ''}: ${m.message}`),
  }));
}
process.exit(failed ? 1 : 0);
