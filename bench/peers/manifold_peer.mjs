// The manifold-3d peer of bench_boolean: reads the operands that the benchmark wrote
// (triangle meshes of its cellforge operands) and the expression, evaluates it with
// Manifold's batch Booleans, and prints "key value" lines for the benchmark to read.
//
//   node manifold_peer.mjs PEERS_DIR MESH_FILE
//
// PEERS_DIR holds node_modules/manifold-3d (bench/peers/setup.sh installs it there).
// MESH_FILE: "CFBOOL1\0", uint32 operand count, uint32 expression length, the expression
// ("D(0,U(1,2))": D difference, U union, I intersection, numbers operands), then per
// operand uint32 vertex and triangle counts, float64 x y z per vertex, uint32 triangles,
// all little-endian.
//
// Timed: building each Mesh and Manifold from typed arrays in memory, the Booleans, and
// forcing the deferred result (numTri). The JS Mesh holds float32 positions, so the
// doubles are narrowed before the clock starts.
import {readFileSync, writeFileSync} from 'node:fs';
import {pathToFileURL} from 'node:url';

const [peersDir, meshFile] = process.argv.slice(2);
const manifoldJs = pathToFileURL(`${peersDir}/node_modules/manifold-3d/manifold.js`).href;
const wasm = await (await import(manifoldJs)).default();
wasm.setup();
const {Manifold, Mesh} = wasm;

function readInput(path) {
  const buf = readFileSync(path);
  if (buf.toString('latin1', 0, 7) !== 'CFBOOL1') throw new Error(`${path}: not a mesh file`);
  let off = 8;
  const u32 = () => { const v = buf.readUInt32LE(off); off += 4; return v; };
  const count = u32();
  const exprLength = u32();
  const expr = buf.toString('latin1', off, off + exprLength);
  off += exprLength;
  const operands = [];
  for (let i = 0; i < count; ++i) {
    const nv = u32(), nt = u32();
    const xyz = new Float64Array(buf.buffer.slice(buf.byteOffset + off, buf.byteOffset + off + 24 * nv));
    off += 24 * nv;
    const tris = new Uint32Array(buf.buffer.slice(buf.byteOffset + off, buf.byteOffset + off + 12 * nt));
    off += 12 * nt;
    operands.push({vertProperties: Float32Array.from(xyz), triVerts: tris});
  }
  return {operands, expr: parseExpr(expr)};
}

// "D(0,U(1,2))" -> {op: 'D', children: [{operand: 0}, {op: 'U', children: [...]}]}
function parseExpr(text) {
  let i = 0;
  const node = () => {
    if (/[0-9]/.test(text[i])) {
      let j = i;
      while (j < text.length && /[0-9]/.test(text[j])) ++j;
      const operand = Number(text.slice(i, j));
      i = j;
      return {operand};
    }
    const op = text[i];
    i += 2;  // the letter and '('
    const children = [node()];
    while (text[i] === ',') { ++i; children.push(node()); }
    ++i;  // ')'
    return {op, children};
  };
  return node();
}

function evaluate(operands, e, made) {
  const keep = (m) => { made.push(m); return m; };
  if (e.operand !== undefined) {
    const mesh = new Mesh({numProp: 3, ...operands[e.operand]});
    return keep(new Manifold(mesh));
  }
  const children = e.children.map((c) => evaluate(operands, c, made));
  if (e.op === 'U') return keep(Manifold.union(children));
  if (e.op === 'I') return keep(Manifold.intersection(children));
  return keep(Manifold.difference(children));
}

function statusKb(field) {
  const m = readFileSync('/proc/self/status', 'latin1').match(new RegExp(`${field}:\\s+(\\d+)`));
  return m ? Number(m[1]) : 0;
}

const {operands, expr} = readInput(meshFile);
const now = () => Number(process.hrtime.bigint()) / 1e9;

// The first run measures memory: the peak above the resident size before it.
let base = 0;
try {
  writeFileSync('/proc/self/clear_refs', '5');
  base = statusKb('VmRSS');
} catch { /* no peak reset here: report 0 */ }

const times = [];
let out = {};
const budget = Number(process.env.CELLFORGE_BENCH_BUDGET ?? 20);
let target = 1;
for (let run = 0; run < target; ++run) {
  const made = [];
  const t0 = now();
  const result = evaluate(operands, expr, made);
  const triangles = result.numTri();
  times.push(now() - t0);
  if (run === 0) {
    const peak = base ? statusKb('VmHWM') - base : 0;
    out = {peak_mb: peak / 1024, out_vertices: result.numVert(), out_triangles: triangles,
           volume: result.volume(), status: result.status()};
    target = times[0] < 0.01 ? 31 : times[0] < 1 ? 5 : 1;
  }
  for (const m of made) m.delete();
  if (times.reduce((a, b) => a + b, 0) > budget) break;
}
times.sort((a, b) => a - b);
out.seconds = times[Math.floor((times.length - 1) / 2)];
out.runs = times.length;
out.in_triangles = operands.reduce((n, o) => n + o.triVerts.length / 3, 0);
for (const [k, v] of Object.entries(out)) console.log(`${k} ${v}`);
