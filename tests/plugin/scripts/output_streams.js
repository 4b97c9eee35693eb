// Script output goes to stdout; log lines to stderr with their prefixes.
print("print line");
console.log("console.log line", 42);
console.info("console.info line");
core.print("core.print line");
core.log("core.log line");
core.warn("core.warn line");
console.warn("console.warn line");
console.error("console.error line");
const grid = core.loadObject(core.scriptArguments()[0] + "/grid3x3.obj");
multirescloth.refineUniform(grid, 1);
