// Validates glTF files with Khronos's glTF-Validator (npm `gltf-validator`): one JSON line per
// file with the counts of errors, warnings, infos and hints and the first messages.
// Usage: node gltf-validate.mjs FILE.glb [FILE.glb ...]
import { readFile } from 'node:fs/promises';
import validator from 'gltf-validator';

for (const file of process.argv.slice(2)) {
  const bytes = new Uint8Array(await readFile(file));
  const report = await validator.validateBytes(bytes, { maxIssues: 50 });
  const issues = report.issues;
  console.log(JSON.stringify({
    file,
    validator: report.validatorVersion,
    errors: issues.numErrors,
    warnings: issues.numWarnings,
    infos: issues.numInfos,
    hints: issues.numHints,
    messages: issues.messages.slice(0, 8).map((m) => `${m.code}: ${m.message} (${m.pointer ?? ''})`),
  }));
}
