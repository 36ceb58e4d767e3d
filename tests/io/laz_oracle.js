// Decodes a LAZ file with laz-perf (npm, a WebAssembly build of an independent LAZ decoder) and
// prints every point's fields as text, one point a line, for the LAZ tests to compare with
// treesketch's decoder. Usage: node laz_oracle.js MODULE_DIR FILE.laz
//   MODULE_DIR: the folder holding node_modules/laz-perf.
// Output: a first line "format F length L count N", then per point:
//   X Y Z intensity return number-of-returns flags classification user-data scan-angle source
//   [gps-time as the 16 hex digits of its bits] [R G B] [NIR] [extra bytes in hex]
// (X Y Z: the stored integers, before scale and offset.)
'use strict';
const fs = require('fs');
const path = require('path');

async function main() {
  const [moduleDir, file, mode] = process.argv.slice(2);
  if (!moduleDir || !file) {
    process.stderr.write('usage: node laz_oracle.js MODULE_DIR FILE.laz\n');
    process.exit(2);
  }
  const {createLazPerf} = require(path.join(path.resolve(moduleDir), 'node_modules', 'laz-perf'));
  const lp = await createLazPerf();
  const bytes = fs.readFileSync(file);
  const filePtr = lp._malloc(bytes.length);
  lp.HEAPU8.set(bytes, filePtr);
  if (mode === '--time') {
    let best = Infinity, n = 0;
    for (let r = 0; r < 3; ++r) {
      const t0 = process.hrtime.bigint();
      const z = new lp.LASZip();
      z.open(filePtr, bytes.length);
      n = z.getCount();
      const p = lp._malloc(z.getPointLength());
      for (let i = 0; i < n; ++i) z.getPoint(p);
      z.delete();
      lp._free(p);
      best = Math.min(best, Number(process.hrtime.bigint() - t0) / 1e9);
    }
    process.stdout.write(`${n} ${best}\n`);
    return;
  }
  const laszip = new lp.LASZip();
  laszip.open(filePtr, bytes.length);
  const format = laszip.getPointFormat();
  const length = laszip.getPointLength();
  const count = laszip.getCount();
  const pointPtr = lp._malloc(length);
  const out = [`format ${format} length ${length} count ${count}`];
  const hex = (v, n) => v.toString(16).padStart(n, '0');
  for (let i = 0; i < count; ++i) {
    laszip.getPoint(pointPtr);
    const b = Buffer.from(lp.HEAPU8.buffer, pointPtr, length);
    const f = [b.readInt32LE(0), b.readInt32LE(4), b.readInt32LE(8), b.readUInt16LE(12)];
    let next;
    if (format >= 6) {
      f.push(b[14] & 15, b[14] >> 4, b[15], b[16], b[17], b.readInt16LE(18), b.readUInt16LE(20));
      f.push(hex(b.readBigUInt64LE(22), 16));
      next = 30;
    } else {
      f.push(b[14] & 7, (b[14] >> 3) & 7, b[14] >> 6, b[15], b[17], b.readInt8(16), b.readUInt16LE(18));
      next = 20;
      if (format === 1 || format === 3) {
        f.push(hex(b.readBigUInt64LE(20), 16));
        next = 28;
      }
    }
    if (format === 2 || format === 3 || format === 7 || format === 8) {
      f.push(b.readUInt16LE(next), b.readUInt16LE(next + 2), b.readUInt16LE(next + 4));
      next += 6;
    }
    if (format === 8) {
      f.push(b.readUInt16LE(next));
      next += 2;
    }
    if (next < length) f.push(b.subarray(next, length).toString('hex'));
    out.push(f.join(' '));
    if (out.length >= 65536) {
      fs.writeSync(1, out.join('\n') + '\n');
      out.length = 0;
    }
  }
  fs.writeSync(1, out.join('\n') + (out.length ? '\n' : ''));
  laszip.delete();
}

main().catch((e) => {
  process.stderr.write(`laz_oracle: ${e && e.message ? e.message : e}\n`);
  process.exit(1);
});
