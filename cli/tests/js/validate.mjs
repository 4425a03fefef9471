// Validates a glTF or GLB file with the Khronos glTF validator and prints its issue counts and
// first messages as one JSON line: node validate.mjs FILE
import { readFileSync } from 'node:fs';
import validator from 'gltf-validator';

const path = process.argv[2];
const report = await validator.validateBytes(new Uint8Array(readFileSync(path)), { maxIssues: 100 });
const { numErrors, numWarnings, numInfos, messages } = report.issues;
console.log(JSON.stringify({ numErrors, numWarnings, numInfos, messages: messages.slice(0, 20) }));
