// Validates glTF files (.glb, .gltf) with the Khronos glTF validator (the
// `gltf-validator` npm package, pinned in package.json). Prints one line
// per file, `FILE errors warnings`, and each issue; exits 1 when any file
// has an error or a warning. Run by tests/integration/space.rs.
import { readFileSync } from 'node:fs';
import validator from 'gltf-validator';

let bad = 0;
for (const file of process.argv.slice(2)) {
  const report = await validator.validateBytes(new Uint8Array(readFileSync(file)), {
    uri: file,
    externalResourceFunction: () => Promise.reject(new Error('no external resources')),
  });
  const { numErrors, numWarnings, messages } = report.issues;
  console.log(`${file} ${numErrors} ${numWarnings}`);
  for (const m of messages) {
    console.log(`  ${m.code} ${m.pointer ?? ''} ${m.message}`);
  }
  if (numErrors > 0 || numWarnings > 0) {
    bad += 1;
  }
}
process.exit(bad > 0 ? 1 : 0);
