// SPDX-License-Identifier: GPL-3.0-or-later
// Validates a .glb/.gltf with the Khronos glTF validator: prints the issue summary as JSON and
// exits 0 when there are no errors, 1 when there are, 2 when it could not run.
'use strict';
const fs = require('fs');
let validator;
try {
  validator = require('gltf-validator');
} catch (e) {
  console.log('gltf-validator is not installed');
  process.exit(3);
}
const file = process.argv[2];
const data = new Uint8Array(fs.readFileSync(file));
validator.validateBytes(data, {maxIssues: 200})
  .then((report) => {
    console.log(JSON.stringify({issues: report.issues, info: report.info}, null, 1));
    process.exit(report.issues.numErrors === 0 ? 0 : 1);
  })
  .catch((error) => {
    console.log('validator failed: ' + error);
    process.exit(2);
  });
