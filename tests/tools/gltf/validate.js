// Validate GLB files with the Khronos glTF-Validator; print one JSON line
// per file: {"file", "errors", "warnings", "messages"}; exit 0 when no file
// has an error or a warning, 2 otherwise.
// Usage: node validate.js FILE.glb...
const fs = require("fs");
const validator = require("gltf-validator");
(async () => {
  let issues = 0;
  for (const file of process.argv.slice(2)) {
    const data = new Uint8Array(fs.readFileSync(file));
    const report = await validator.validateBytes(data, { maxIssues: 100 });
    const messages = report.issues.messages
      .filter((m) => m.severity <= 1)
      .map((m) => `${m.severity === 0 ? "error" : "warning"} ${m.code} ${m.pointer || ""}: ${m.message}`);
    console.log(JSON.stringify({
      file,
      errors: report.issues.numErrors,
      warnings: report.issues.numWarnings,
      messages,
    }));
    issues += report.issues.numErrors + report.issues.numWarnings;
  }
  process.exitCode = issues ? 2 : 0;
})().catch((e) => { console.error(String(e)); process.exit(1); });
