// Runs the Khronos glTF validator (npm package gltf-validator) on one .glb or .gltf file.
//
// usage: node validate_gltf.js NODE_MODULES_DIR FILE
//
// Prints one summary line, "errors E warnings W infos I hints H", then one line per issue
// ("severity code pointer: message"), and exits 0 when the validator ran (whatever it found),
// 2 when it could not run. glb_test.cpp reads the summary line.
'use strict';

const fs = require('fs');
const path = require('path');

const [modules, file] = process.argv.slice(2);
if (!modules || !file) {
  console.error('usage: node validate_gltf.js NODE_MODULES_DIR FILE');
  process.exit(2);
}

const validator = require(path.join(path.resolve(modules), 'gltf-validator'));
const severities = ['error', 'warning', 'info', 'hint'];

validator.validateBytes(new Uint8Array(fs.readFileSync(file)), {
  uri: path.basename(file),
  maxIssues: 0,  // all of them
  // A .glb from our exporter embeds everything; any request for an outside file is a finding.
  externalResourceFunction: (uri) => Promise.reject(new Error(`external resource requested: ${uri}`)),
}).then((report) => {
  const i = report.issues;
  console.log(`errors ${i.numErrors} warnings ${i.numWarnings} infos ${i.numInfos} hints ${i.numHints}`);
  for (const m of i.messages) {
    console.log(`${severities[m.severity] || m.severity} ${m.code} ${m.pointer || m.offset || ''}: ${m.message}`);
  }
  process.exit(0);
}).catch((e) => {
  console.error(`validator failed: ${e && e.stack ? e.stack : e}`);
  process.exit(2);
});
