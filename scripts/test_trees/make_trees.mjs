// Writes procedural test trees made with the ez-tree generator (npm: @dgreenheck/ez-tree), in the
// layout of ../shared/data/trees that `treesketch evaluate --trees` and `classify --evaluate` read:
// <name>.branches.obj (the tubes), <name>.leaves.obj (the leaf quads) and <name>.json (the options
// and the exact skeleton: every tube's rings with centre, radius and axis, and the limbs).
// The generator is a test oracle only: trees it makes are measured against, never shipped.
//
//   node make_trees.mjs OUT_DIR "Oak Large:101" "Bush 1:202" ...      (preset:seed pairs)
//
// Run through make_trees.sh, which installs the generator into a scratch folder first.
import { writeFileSync, mkdirSync, renameSync } from 'node:fs';
import { join } from 'node:path';

// The generator loads its bark and leaf textures when imported, which wants a browser's document;
// the textures are not used here, so a document whose images never load stands in for it.
globalThis.document ??= {
  createElementNS: () => ({ addEventListener() {}, removeEventListener() {}, style: {} }),
};
const { Tree, TreePreset } = await import('@dgreenheck/ez-tree');

/// A tree that records what it grows: per tube its ring vertices, level, parent and how it joins it.
class RecordingTree extends Tree {
  constructor() {
    super();  // the generator's default options, overwritten by a preset below
    this.tubes = [];
    this.current = -1;
    this.attachNext = 'root';
  }

  generate() {
    this.tubes = [];
    this.current = -1;
    const queuePush = this.branchQueue.push.bind(this.branchQueue);
    // Every branch queued while another is grown is that one's child; note which and how.
    this.branchQueue.push = (...items) => {
      for (const b of items) {
        b.recordedParent = this.current;
        b.recordedAttach = this.current < 0 ? 'root' : this.attachNext;
      }
      return queuePush(...items);
    };
    super.generate();
    this.branchQueue.push = queuePush;
  }

  generateBranch(branch) {
    const first = this.branches.verts.length / 3;
    const id = this.tubes.length;
    this.tubes.push({
      id,
      parent: branch.recordedParent ?? -1,
      attach: branch.recordedAttach ?? 'root',
      level: branch.level,
      segments: branch.segmentCount,
      sections: branch.sectionCount,
      firstVertex: first,
    });
    const previous = this.current;
    this.current = id;
    this.attachNext = 'terminal';  // the continuation is queued from the branch itself
    super.generateBranch(branch);
    this.current = previous;
  }

  generateChildBranches(count, level, sections) {
    this.attachNext = 'lateral';
    super.generateChildBranches(count, level, sections);
    this.attachNext = 'terminal';
  }

  // Geometry and materials for drawing are not needed (and want a browser for their textures).
  createBranchesGeometry() {}
  createLeavesGeometry() {}
  createTrellis() {}
}

function vertex(verts, i) {
  return [verts[3 * i], verts[3 * i + 1], verts[3 * i + 2]];
}
const sub = (a, b) => [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
const dot = (a, b) => a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
const cross = (a, b) => [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]];
const norm = (a) => Math.sqrt(dot(a, a));
const unit = (a) => {
  const n = norm(a);
  return n > 0 ? a.map((x) => x / n) : [0, 1, 0];
};
const fmt = (x) => Number(x.toFixed(6));

/// Each tube's rings: centre (the mean of its polygon's corners), radius (centre to a corner) and
/// axis (the ring's normal, pointing along the tube).
function tubeSections(tree, tube) {
  const verts = tree.branches.verts;
  const perRing = tube.segments + 1;  // the generator repeats the first corner at the seam
  const rings = [];
  for (let r = 0; r <= tube.sections; ++r) {
    const base = tube.firstVertex + r * perRing;
    const c = [0, 0, 0];
    for (let j = 0; j < tube.segments; ++j) {
      const v = vertex(verts, base + j);
      c[0] += v[0] / tube.segments;
      c[1] += v[1] / tube.segments;
      c[2] += v[2] / tube.segments;
    }
    const v0 = sub(vertex(verts, base), c);
    const v1 = sub(vertex(verts, base + 1), c);
    rings.push({ center: c, radius: norm(v0), normal: unit(cross(v1, v0)) });
  }
  for (let r = 0; r < rings.length; ++r) {
    const along = r + 1 < rings.length ? sub(rings[r + 1].center, rings[r].center) : sub(rings[r].center, rings[r - 1].center);
    if (dot(rings[r].normal, along) < 0) rings[r].normal = rings[r].normal.map((x) => -x);
  }
  return rings.map((s) => ({ center: s.center.map(fmt), radius: fmt(s.radius), axis: s.normal.map(fmt) }));
}

/// The branch tubes as one OBJ: each tube's rings without the seam's repeat, quads split in two,
/// counter-clockwise seen from outside.
function branchesObj(tree) {
  const lines = ['# tree tubes (ez-tree), Y up', 'o branches'];
  const faces = [];
  let next = 1;
  for (const tube of tree.tubes) {
    const perRing = tube.segments + 1;
    const start = next;
    for (let r = 0; r <= tube.sections; ++r)
      for (let j = 0; j < tube.segments; ++j) {
        const v = vertex(tree.branches.verts, tube.firstVertex + r * perRing + j);
        lines.push(`v ${v[0].toFixed(6)} ${v[1].toFixed(6)} ${v[2].toFixed(6)}`);
        ++next;
      }
    for (let r = 0; r < tube.sections; ++r)
      for (let j = 0; j < tube.segments; ++j) {
        const a = start + r * tube.segments + j;
        const b = start + r * tube.segments + ((j + 1) % tube.segments);
        const c = a + tube.segments;
        const d = b + tube.segments;
        faces.push(`f ${a} ${c} ${b}`, `f ${b} ${c} ${d}`);
      }
  }
  return lines.concat(faces).join('\n') + '\n';
}

function leavesObj(tree) {
  const lines = ['# leaf quads (ez-tree), Y up', 'o leaves'];
  const v = tree.leaves.verts;
  for (let i = 0; i < v.length; i += 3) lines.push(`v ${v[i].toFixed(6)} ${v[i + 1].toFixed(6)} ${v[i + 2].toFixed(6)}`);
  const idx = tree.leaves.indices;
  for (let i = 0; i < idx.length; i += 3) lines.push(`f ${idx[i] + 1} ${idx[i + 1] + 1} ${idx[i + 2] + 1}`);
  return lines.join('\n') + '\n';
}

/// Limbs: each root or lateral tube with its chain of terminal continuations, as one axis.
function limbsOf(tubes, sections) {
  const continuation = new Map();
  for (const t of tubes) if (t.attach === 'terminal') continuation.set(t.parent, t.id);
  const limbOfTube = new Map();
  const limbs = [];
  for (const t of tubes) {
    if (t.attach === 'terminal') continue;
    const limb = { id: limbs.length, branches: [], parent_limb: null, sections: [] };
    for (let id = t.id; id !== undefined; id = continuation.get(id)) {
      limb.branches.push(id);
      limbOfTube.set(id, limb.id);
      const s = sections[id];
      limb.sections.push(...(limb.sections.length > 0 ? s.slice(1) : s));  // a continuation starts at its parent's last ring
    }
    limb.rootTube = t;
    limbs.push(limb);
  }
  for (const limb of limbs) {
    if (limb.rootTube.parent >= 0) limb.parent_limb = limbOfTube.get(limb.rootTube.parent);
    delete limb.rootTube;
  }
  return limbs;
}

function writeAtomically(path, text) {
  writeFileSync(path + '.tmp', text);
  renameSync(path + '.tmp', path);
}

function makeTree(outDir, presetName, seed) {
  if (!(presetName in TreePreset)) throw new Error(`unknown preset '${presetName}' (known: ${Object.keys(TreePreset).join(', ')})`);
  const tree = new RecordingTree();
  tree.options.copy(TreePreset[presetName]);
  tree.options.seed = seed;
  const options = tree.options;
  tree.generate();
  const sections = tree.tubes.map((t) => tubeSections(tree, t));
  const name = `${presetName.toLowerCase().replace(/ /g, '_')}_s${seed}`;
  let height = 0;
  for (let i = 1; i < tree.branches.verts.length; i += 3) height = Math.max(height, tree.branches.verts[i]);
  const doc = {
    name,
    generator: '@dgreenheck/ez-tree (npm), run by scripts/test_trees/make_trees.mjs',
    preset: presetName,
    seed,
    height: fmt(height),
    options,
    skeleton: {
      branches: tree.tubes.map((t) => ({
        id: t.id,
        parent: t.parent >= 0 ? t.parent : null,
        attach: t.attach,
        level: t.level,
        section_count: t.sections,
        segment_count: t.segments,
        sections: sections[t.id],
      })),
      limbs: limbsOf(tree.tubes, sections),
    },
  };
  writeAtomically(join(outDir, `${name}.branches.obj`), branchesObj(tree));
  writeAtomically(join(outDir, `${name}.leaves.obj`), leavesObj(tree));
  writeAtomically(join(outDir, `${name}.json`), JSON.stringify(doc));
  return { name, tubes: tree.tubes.length, limbs: doc.skeleton.limbs.length, leaves: tree.leaves.indices.length / 6, height };
}

const [outDir, ...specs] = process.argv.slice(2);
if (!outDir || specs.length === 0) {
  console.error('usage: node make_trees.mjs OUT_DIR "Preset Name:seed" ...');
  process.exit(2);
}
mkdirSync(outDir, { recursive: true });
for (const spec of specs) {
  const at = spec.lastIndexOf(':');
  const seed = Number(spec.slice(at + 1));
  if (at < 0 || !Number.isInteger(seed)) {
    console.error(`${spec}: expected "Preset Name:seed" (an integer seed)`);
    process.exit(2);
  }
  const t = makeTree(outDir, spec.slice(0, at), seed);
  console.log(`${t.name}: ${t.tubes} tubes, ${t.limbs} limbs, ${t.leaves} leaf quads, height ${t.height.toFixed(2)}`);
}
