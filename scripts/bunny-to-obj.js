// Converts the npm `bunny` package (positions and cells arrays) to Wavefront OBJ.
// Usage: node bunny-to-obj.js PACKAGE_DIR OUT.obj
const fs = require('fs');
const path = require('path');
const [pkgDir, out] = process.argv.slice(2);
const bunny = require(path.resolve(pkgDir));
const lines = ['# Stanford bunny, from the npm package `bunny` (positions, cells)'];
for (const [x, y, z] of bunny.positions) lines.push(`v ${x} ${y} ${z}`);
for (const [a, b, c] of bunny.cells) lines.push(`f ${a + 1} ${b + 1} ${c + 1}`);
fs.writeFileSync(out, lines.join('\n') + '\n');
console.log(`bunny: ${bunny.positions.length} vertices, ${bunny.cells.length} triangles -> ${out}`);
