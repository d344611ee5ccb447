// Runs Khronos' glTF-Validator (the npm package gltf-validator) on one file and prints one line:
// NAME <tab> ERRORS <tab> CODES, CODES being the distinct error codes with their JSON pointers.
// One process per file: the validator's JSON reader recurses, and a file nested deeper than node's
// stack ends the process (reported by tools/validate-corpus, not here).
// External resources resolve inside the file's folder only, as the player resolves them.
const fs = require('fs');
const path = require('path');
const validator = require(process.env.GLTF_VALIDATOR);

const file = process.argv[2];
const folder = path.resolve(path.dirname(file));
const name = path.basename(file);

validator
  .validateBytes(new Uint8Array(fs.readFileSync(file)), {
    uri: name,
    format: name.endsWith('.glb') ? 'glb' : 'gltf',
    maxIssues: 0,
    externalResourceFunction: (uri) =>
      new Promise((resolve, reject) => {
        const target = path.resolve(folder, decodeURIComponent(uri));
        if (!target.startsWith(folder + path.sep)) return reject(new Error(`${uri} is outside the folder`));
        fs.readFile(target, (error, bytes) => (error ? reject(error) : resolve(new Uint8Array(bytes))));
      }),
  })
  .then((report) => {
    const codes = report.issues.messages
      .filter((message) => message.severity === 0)
      .map((message) => message.code + (message.pointer ? '@' + message.pointer : ''));
    console.log([name, report.issues.numErrors, [...new Set(codes)].join(',')].join('\t'));
  })
  .catch((error) => {
    console.log([name, -1, 'VALIDATOR_FAILED:' + String(error).replace(/\s+/g, ' ').slice(0, 120)].join('\t'));
  });
