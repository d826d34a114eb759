// village_instanced.wgsl — examples/village.sdf, a copy of runtime/benches/reference/village.wgsl
// (same tracer, constants, output; every shape function byte-for-byte the same)
// whose map() does NOT write out the repeated copies: houses (10), town houses (3), blocks (6) and
// trees (8 per side, the two sides folded onto one by abs(p.z) exactly as village.wgsl does) are
// data: a constant list of translations per kind, enumerated by ONE data-driven loop.
//
// Structure of parts(p) (map() uses it):
//   1. The single parts first: ground plane, road slab, church. Their min seeds the running min.
//   2. Per kind, a lower bound b_j = |gap from p to copy j's bounding box|² for every copy j. The
//      box is the kind's (known, constant) local bounding box, half extents padded by 1e-3, moved
//      by the copy's translation. The gaps are separable, so one gap² per distinct x, y, z of the
//      translations is computed and b_j is a sum of three of them.
//   3. Per kind, k = the copy with the smallest b_j (select chain, no loop).
//   4. ONE loop for all four kinds in lockstep (uniform code: no per-lane switch between kinds):
//      each trip evaluates, for every kind, the copy k of that kind (translation from k by a select
//      ladder over the constant translations), then sets lim = max(running min over everything,
//      0) and rebuilds each kind's candidate bitmask m = {j : b_j <= lim², j not yet evaluated}.
//      The loop ends when every kind's mask is empty in every lane; otherwise k = lowest set bit
//      (a kind with an empty mask re-evaluates its last copy, which leaves the min unchanged).
//      Trip 1 is the nearest-box copy of each kind; llvmpipe runs a loop until all 8 lanes leave
//      it, and measured trips here average ~1.03 per lane.
//   Exactness: a copy is left out only when its box is farther than the running minimum at that
//   moment, so its field (>= its box distance) cannot be the minimum: the field is exactly the min
//   over all copies.
//
// Tracer: basic sphere tracing, 200 steps, ε(t) = max(view.size.z·t, 2.0995714e-4),
// max_distance 80, p advanced by p += rd·d; no hit confirmation (every part is exact, as in
// village.wgsl). Output: out[i] = (bitcast(t), steps | hit << 31).
//
// Written for issue 14 (by a generator from village.wgsl, variant "F": the lockstep loop) to
// measure whether a data-driven loop over the copies pays on lavapipe: see docs/benchmarks.md.

struct View {
    eye: vec4<f32>,
    right: vec4<f32>,
    up: vec4<f32>,
    forward: vec4<f32>,
    size: vec4<f32>,
    offset: vec4<u32>,
}

@group(0) @binding(0) var<uniform> view: View;
@group(0) @binding(1) var<storage, read_write> out: array<vec2<u32>>;

const STEPS: u32 = 200u;
const EPS_FLOOR: f32 = 0.00020995714;
const MAX_T: f32 = 80.0;
const C45: f32 = 0.70710677;

// b: half extents.
fn box3(p: vec3<f32>, b: vec3<f32>) -> f32 {
    let q = abs(p) - b;
    return length(max(q, vec3<f32>(0.0))) + min(max(q.x, max(q.y, q.z)), 0.0);
}

// Capped cone around y, apex at y = +h, base radius r at y = −h; k = 1 / (r² + 4h²).
fn cone(p: vec3<f32>, r: f32, h: f32, k: f32) -> f32 {
    let qx = length(p.xz);
    let ca = vec2<f32>(select(qx, max(qx - r, 0.0), p.y < 0.0), abs(p.y) - h);
    let s = clamp((r * qx + 2.0 * h * (h - p.y)) * k, 0.0, 1.0);
    let cb = vec2<f32>(qx - r * s, p.y - h + 2.0 * h * s);
    let inside = 2.0 * h * qx + r * (p.y - h) < 0.0 && ca.y < 0.0;
    return select(1.0, -1.0, inside) * sqrt(min(dot(ca, ca), dot(cb, cb)));
}

// Gabled house: walls, a square prism turned 45° about z as the roof, a chimney.
fn house(q: vec3<f32>) -> f32 {
    var d = box3(q - vec3<f32>(0.0, 0.5, 0.0), vec3<f32>(0.7, 0.5, 0.55));
    let r = q - vec3<f32>(0.0, 1.0, 0.0);
    d = min(d, box3(vec3<f32>(C45 * (r.x + r.y), C45 * (r.y - r.x), r.z), vec3<f32>(0.51, 0.51, 0.65)));
    return min(d, box3(q - vec3<f32>(0.0, 1.6, 0.0), vec3<f32>(0.09, 0.45, 0.09)));
}

// Town house parts (walls, roof, annex): the roof is a 1.035 × 0.9 × 0.9 box turned 45° about x
// (the scene's 0.9 cube stretched 1.15 along x, which sdfc takes into the box's size).
fn townhouse(q: vec3<f32>) -> vec3<f32> {
    let walls = box3(q - vec3<f32>(0.0, 0.9, 0.0), vec3<f32>(0.5, 0.9, 0.6));
    let s = vec3<f32>(q.x, q.y - 1.8, q.z);
    let roof = box3(vec3<f32>(s.x, C45 * (s.y + s.z), C45 * (s.z - s.y)), vec3<f32>(0.5175, 0.45, 0.45));
    let annex = box3(q - vec3<f32>(0.0, 0.35, 0.0), vec3<f32>(0.65, 0.35, 0.45));
    return vec3<f32>(walls, roof, annex);
}

fn block(q: vec3<f32>) -> f32 {
    return min(box3(q - vec3<f32>(0.0, 1.3, 0.0), vec3<f32>(0.75, 1.3, 0.75)),
               box3(q - vec3<f32>(0.0, 2.8, 0.0), vec3<f32>(0.35, 0.2, 0.35)));
}

fn tree(q: vec3<f32>) -> f32 {
    let t = abs(vec2<f32>(length(q.xz), q.y - 0.25)) - vec2<f32>(0.08, 0.25);
    let trunk = min(max(t.x, t.y), 0.0) + length(max(t, vec2<f32>(0.0)));
    return min(trunk, cone(q - vec3<f32>(0.0, 1.1, 0.0), 0.42, 0.65, 0.53579083));
}

// The copies of each repeated kind: translations (the tree row in the z-folded space).
const HOUSE_T = array<vec3<f32>, 10>(
    vec3<f32>(-7.0, 0.0, -5.6),
    vec3<f32>(-4.0, 0.0, -5.6),
    vec3<f32>(-1.0, 0.0, -5.6),
    vec3<f32>(2.0, 0.0, -5.6),
    vec3<f32>(5.0, 0.0, -5.6),
    vec3<f32>(-7.0, 0.0, -2.4),
    vec3<f32>(-4.0, 0.0, -2.4),
    vec3<f32>(-1.0, 0.0, -2.4),
    vec3<f32>(2.0, 0.0, -2.4),
    vec3<f32>(5.0, 0.0, -2.4));
const TOWNHOUSE_T = array<vec3<f32>, 3>(
    vec3<f32>(-6.8, 0.0, 2.6),
    vec3<f32>(-3.5, 0.0, 2.6),
    vec3<f32>(-0.2, 0.0, 2.6));
const BLOCK_T = array<vec3<f32>, 6>(
    vec3<f32>(-7.4, 0.0, 4.7),
    vec3<f32>(-3.6, 0.0, 4.7),
    vec3<f32>(0.2, 0.0, 4.7),
    vec3<f32>(-7.4, 0.0, 8.5),
    vec3<f32>(-3.6, 0.0, 8.5),
    vec3<f32>(0.2, 0.0, 8.5));
const TREE_T = array<vec3<f32>, 8>(
    vec3<f32>(-6.45, 0.0, 0.0),
    vec3<f32>(-4.55, 0.0, 0.0),
    vec3<f32>(-2.65, 0.0, 0.0),
    vec3<f32>(-0.75, 0.0, 0.0),
    vec3<f32>(1.15, 0.0, 0.0),
    vec3<f32>(3.05, 0.0, 0.0),
    vec3<f32>(4.95, 0.0, 0.0),
    vec3<f32>(6.85, 0.0, 0.0));

struct Parts {
    h: f32,          // houses
    t: vec3<f32>,    // town houses: (walls, roof, annex)
    r: f32,          // the rest: blocks, church, trees, road, ground
}

fn church(p: vec3<f32>) -> f32 {
    // Church at (4.3, 0, 5.2), turned 90° about y: local (x, y, z) = (5.2 − pz, py, px − 4.3).
    let c = vec3<f32>(5.2 - p.z, p.y, p.x - 4.3);
    var d = box3(c - vec3<f32>(0.0, 0.8, 0.0), vec3<f32>(0.8, 0.8, 1.6));
    let r = c - vec3<f32>(0.0, 1.6, 0.0);
    d = min(d, box3(vec3<f32>(C45 * (r.x + r.y), C45 * (r.y - r.x), r.z), vec3<f32>(0.6, 0.6, 1.65)));
    d = min(d, box3(c - vec3<f32>(0.0, 1.7, -2.0), vec3<f32>(0.5, 1.7, 0.5)));
    return min(d, cone(c - vec3<f32>(0.0, 4.3, -2.0), 0.72, 0.9, 0.26607067));
}

fn parts(p: vec3<f32>) -> Parts {
    let r = min(min(p.y, box3(p, vec3<f32>(11.0, 0.02, 0.65))), church(p));
    let m = vec3<f32>(p.x, p.y, abs(p.z) - 1.05);   // trees: z folded onto the row at z = +1.05
    // tree: 8 copies
    let egx0 = max(abs(m.x - -6.45) - 0.421, 0.0); let egx02 = egx0 * egx0;
    let egx1 = max(abs(m.x - -4.55) - 0.421, 0.0); let egx12 = egx1 * egx1;
    let egx2 = max(abs(m.x - -2.65) - 0.421, 0.0); let egx22 = egx2 * egx2;
    let egx3 = max(abs(m.x - -0.75) - 0.421, 0.0); let egx32 = egx3 * egx3;
    let egx4 = max(abs(m.x - 1.15) - 0.421, 0.0); let egx42 = egx4 * egx4;
    let egx5 = max(abs(m.x - 3.05) - 0.421, 0.0); let egx52 = egx5 * egx5;
    let egx6 = max(abs(m.x - 4.95) - 0.421, 0.0); let egx62 = egx6 * egx6;
    let egx7 = max(abs(m.x - 6.85) - 0.421, 0.0); let egx72 = egx7 * egx7;
    let egy0 = max(abs(m.y - 0.875) - 0.876, 0.0); let egy02 = egy0 * egy0;
    let egz0 = max(abs(m.z - 0.0) - 0.421, 0.0); let egz02 = egz0 * egz0;
    let eb0 = egx02 + egy02 + egz02;
    let eb1 = egx12 + egy02 + egz02;
    let eb2 = egx22 + egy02 + egz02;
    let eb3 = egx32 + egy02 + egz02;
    let eb4 = egx42 + egy02 + egz02;
    let eb5 = egx52 + egy02 + egz02;
    let eb6 = egx62 + egy02 + egz02;
    let eb7 = egx72 + egy02 + egz02;
    let ef0 = eb0;
    let ei0 = 0u;
    let ee1 = eb1 < ef0;
    let ef1 = select(ef0, eb1, ee1);
    let ei1 = select(ei0, 1u, ee1);
    let ee2 = eb2 < ef1;
    let ef2 = select(ef1, eb2, ee2);
    let ei2 = select(ei1, 2u, ee2);
    let ee3 = eb3 < ef2;
    let ef3 = select(ef2, eb3, ee3);
    let ei3 = select(ei2, 3u, ee3);
    let ee4 = eb4 < ef3;
    let ef4 = select(ef3, eb4, ee4);
    let ei4 = select(ei3, 4u, ee4);
    let ee5 = eb5 < ef4;
    let ef5 = select(ef4, eb5, ee5);
    let ei5 = select(ei4, 5u, ee5);
    let ee6 = eb6 < ef5;
    let ef6 = select(ef5, eb6, ee6);
    let ei6 = select(ei5, 6u, ee6);
    let ee7 = eb7 < ef6;
    let ef7 = select(ef6, eb7, ee7);
    let ei7 = select(ei6, 7u, ee7);
    var ek = ei7;
    var edone = 0u;
    // house: 10 copies
    let hgx0 = max(abs(p.x - -7.0) - 0.72225, 0.0); let hgx02 = hgx0 * hgx0;
    let hgx1 = max(abs(p.x - -4.0) - 0.72225, 0.0); let hgx12 = hgx1 * hgx1;
    let hgx2 = max(abs(p.x - -1.0) - 0.72225, 0.0); let hgx22 = hgx2 * hgx2;
    let hgx3 = max(abs(p.x - 2.0) - 0.72225, 0.0); let hgx32 = hgx3 * hgx3;
    let hgx4 = max(abs(p.x - 5.0) - 0.72225, 0.0); let hgx42 = hgx4 * hgx4;
    let hgy0 = max(abs(p.y - 1.025) - 1.0259999999999998, 0.0); let hgy02 = hgy0 * hgy0;
    let hgz0 = max(abs(p.z - -5.6) - 0.651, 0.0); let hgz02 = hgz0 * hgz0;
    let hgz1 = max(abs(p.z - -2.4) - 0.651, 0.0); let hgz12 = hgz1 * hgz1;
    let hb0 = hgx02 + hgy02 + hgz02;
    let hb1 = hgx12 + hgy02 + hgz02;
    let hb2 = hgx22 + hgy02 + hgz02;
    let hb3 = hgx32 + hgy02 + hgz02;
    let hb4 = hgx42 + hgy02 + hgz02;
    let hb5 = hgx02 + hgy02 + hgz12;
    let hb6 = hgx12 + hgy02 + hgz12;
    let hb7 = hgx22 + hgy02 + hgz12;
    let hb8 = hgx32 + hgy02 + hgz12;
    let hb9 = hgx42 + hgy02 + hgz12;
    let hf0 = hb0;
    let hi0 = 0u;
    let he1 = hb1 < hf0;
    let hf1 = select(hf0, hb1, he1);
    let hi1 = select(hi0, 1u, he1);
    let he2 = hb2 < hf1;
    let hf2 = select(hf1, hb2, he2);
    let hi2 = select(hi1, 2u, he2);
    let he3 = hb3 < hf2;
    let hf3 = select(hf2, hb3, he3);
    let hi3 = select(hi2, 3u, he3);
    let he4 = hb4 < hf3;
    let hf4 = select(hf3, hb4, he4);
    let hi4 = select(hi3, 4u, he4);
    let he5 = hb5 < hf4;
    let hf5 = select(hf4, hb5, he5);
    let hi5 = select(hi4, 5u, he5);
    let he6 = hb6 < hf5;
    let hf6 = select(hf5, hb6, he6);
    let hi6 = select(hi5, 6u, he6);
    let he7 = hb7 < hf6;
    let hf7 = select(hf6, hb7, he7);
    let hi7 = select(hi6, 7u, he7);
    let he8 = hb8 < hf7;
    let hf8 = select(hf7, hb8, he8);
    let hi8 = select(hi7, 8u, he8);
    let he9 = hb9 < hf8;
    let hf9 = select(hf8, hb9, he9);
    let hi9 = select(hi8, 9u, he9);
    var hk = hi9;
    var hdone = 0u;
    // townhouse: 3 copies
    let wgx0 = max(abs(p.x - -6.8) - 0.651, 0.0); let wgx02 = wgx0 * wgx0;
    let wgx1 = max(abs(p.x - -3.5) - 0.651, 0.0); let wgx12 = wgx1 * wgx1;
    let wgx2 = max(abs(p.x - -0.2) - 0.651, 0.0); let wgx22 = wgx2 * wgx2;
    let wgy0 = max(abs(p.y - 1.2182) - 1.2191999999999998, 0.0); let wgy02 = wgy0 * wgy0;
    let wgz0 = max(abs(p.z - 2.6) - 0.6374, 0.0); let wgz02 = wgz0 * wgz0;
    let wb0 = wgx02 + wgy02 + wgz02;
    let wb1 = wgx12 + wgy02 + wgz02;
    let wb2 = wgx22 + wgy02 + wgz02;
    let wf0 = wb0;
    let wi0 = 0u;
    let we1 = wb1 < wf0;
    let wf1 = select(wf0, wb1, we1);
    let wi1 = select(wi0, 1u, we1);
    let we2 = wb2 < wf1;
    let wf2 = select(wf1, wb2, we2);
    let wi2 = select(wi1, 2u, we2);
    var wk = wi2;
    var wdone = 0u;
    // block: 6 copies
    let bgx0 = max(abs(p.x - -7.4) - 0.751, 0.0); let bgx02 = bgx0 * bgx0;
    let bgx1 = max(abs(p.x - -3.6) - 0.751, 0.0); let bgx12 = bgx1 * bgx1;
    let bgx2 = max(abs(p.x - 0.2) - 0.751, 0.0); let bgx22 = bgx2 * bgx2;
    let bgy0 = max(abs(p.y - 1.5) - 1.501, 0.0); let bgy02 = bgy0 * bgy0;
    let bgz0 = max(abs(p.z - 4.7) - 0.751, 0.0); let bgz02 = bgz0 * bgz0;
    let bgz1 = max(abs(p.z - 8.5) - 0.751, 0.0); let bgz12 = bgz1 * bgz1;
    let bb0 = bgx02 + bgy02 + bgz02;
    let bb1 = bgx12 + bgy02 + bgz02;
    let bb2 = bgx22 + bgy02 + bgz02;
    let bb3 = bgx02 + bgy02 + bgz12;
    let bb4 = bgx12 + bgy02 + bgz12;
    let bb5 = bgx22 + bgy02 + bgz12;
    let bf0 = bb0;
    let bi0 = 0u;
    let be1 = bb1 < bf0;
    let bf1 = select(bf0, bb1, be1);
    let bi1 = select(bi0, 1u, be1);
    let be2 = bb2 < bf1;
    let bf2 = select(bf1, bb2, be2);
    let bi2 = select(bi1, 2u, be2);
    let be3 = bb3 < bf2;
    let bf3 = select(bf2, bb3, be3);
    let bi3 = select(bi2, 3u, be3);
    let be4 = bb4 < bf3;
    let bf4 = select(bf3, bb4, be4);
    let bi4 = select(bi3, 4u, be4);
    let be5 = bb5 < bf4;
    let bf5 = select(bf4, bb5, be5);
    let bi5 = select(bi4, 5u, be5);
    var bk = bi5;
    var bdone = 0u;
    var h = 3.0e38;
    var t = vec3<f32>(3.0e38);
    var bl = 3.0e38;
    var tr = 3.0e38;
    loop {
        let et0 = TREE_T[0];
        let et1 = select(et0, TREE_T[1], ek == 1u);
        let et2 = select(et1, TREE_T[2], ek == 2u);
        let et3 = select(et2, TREE_T[3], ek == 3u);
        let et4 = select(et3, TREE_T[4], ek == 4u);
        let et5 = select(et4, TREE_T[5], ek == 5u);
        let et6 = select(et5, TREE_T[6], ek == 6u);
        let et7 = select(et6, TREE_T[7], ek == 7u);
        tr = min(tr, tree(m - et7));
        edone |= 1u << ek;
        let ht0 = HOUSE_T[0];
        let ht1 = select(ht0, HOUSE_T[1], hk == 1u);
        let ht2 = select(ht1, HOUSE_T[2], hk == 2u);
        let ht3 = select(ht2, HOUSE_T[3], hk == 3u);
        let ht4 = select(ht3, HOUSE_T[4], hk == 4u);
        let ht5 = select(ht4, HOUSE_T[5], hk == 5u);
        let ht6 = select(ht5, HOUSE_T[6], hk == 6u);
        let ht7 = select(ht6, HOUSE_T[7], hk == 7u);
        let ht8 = select(ht7, HOUSE_T[8], hk == 8u);
        let ht9 = select(ht8, HOUSE_T[9], hk == 9u);
        h = min(h, house(p - ht9));
        hdone |= 1u << hk;
        let wt0 = TOWNHOUSE_T[0];
        let wt1 = select(wt0, TOWNHOUSE_T[1], wk == 1u);
        let wt2 = select(wt1, TOWNHOUSE_T[2], wk == 2u);
        t = min(t, townhouse(p - wt2));
        wdone |= 1u << wk;
        let bt0 = BLOCK_T[0];
        let bt1 = select(bt0, BLOCK_T[1], bk == 1u);
        let bt2 = select(bt1, BLOCK_T[2], bk == 2u);
        let bt3 = select(bt2, BLOCK_T[3], bk == 3u);
        let bt4 = select(bt3, BLOCK_T[4], bk == 4u);
        let bt5 = select(bt4, BLOCK_T[5], bk == 5u);
        bl = min(bl, block(p - bt5));
        bdone |= 1u << bk;
        let lim = max(min(min(min(r, h), min(bl, tr)), min(t.x, min(t.y, t.z))), 0.0);
        let l2 = lim * lim;
        let em = (select(0u, 1u, eb0 <= l2) | select(0u, 2u, eb1 <= l2) | select(0u, 4u, eb2 <= l2) | select(0u, 8u, eb3 <= l2) | select(0u, 16u, eb4 <= l2) | select(0u, 32u, eb5 <= l2) | select(0u, 64u, eb6 <= l2) | select(0u, 128u, eb7 <= l2)) & ~edone;
        let hm = (select(0u, 1u, hb0 <= l2) | select(0u, 2u, hb1 <= l2) | select(0u, 4u, hb2 <= l2) | select(0u, 8u, hb3 <= l2) | select(0u, 16u, hb4 <= l2) | select(0u, 32u, hb5 <= l2) | select(0u, 64u, hb6 <= l2) | select(0u, 128u, hb7 <= l2) | select(0u, 256u, hb8 <= l2) | select(0u, 512u, hb9 <= l2)) & ~hdone;
        let wm = (select(0u, 1u, wb0 <= l2) | select(0u, 2u, wb1 <= l2) | select(0u, 4u, wb2 <= l2)) & ~wdone;
        let bm = (select(0u, 1u, bb0 <= l2) | select(0u, 2u, bb1 <= l2) | select(0u, 4u, bb2 <= l2) | select(0u, 8u, bb3 <= l2) | select(0u, 16u, bb4 <= l2) | select(0u, 32u, bb5 <= l2)) & ~bdone;
        if ((hm | wm | bm | em) == 0u) { break; }
        ek = select(ek, firstTrailingBit(em), em != 0u);
        hk = select(hk, firstTrailingBit(hm), hm != 0u);
        wk = select(wk, firstTrailingBit(wm), wm != 0u);
        bk = select(bk, firstTrailingBit(bm), bm != 0u);
    }
    return Parts(h, t, min(r, min(bl, tr)));
}

fn map(p: vec3<f32>) -> f32 {
    let q = parts(p);
    return min(min(q.h, q.r), min(q.t.x, min(q.t.y, q.t.z)));
}

@compute @workgroup_size(8, 8, 1)
fn main(@builtin(global_invocation_id) gid: vec3<u32>) {
    let px = gid.xy + view.offset.xy;
    if (px.x >= view.offset.z || px.y >= view.offset.w) {
        return;
    }
    let index = px.y * view.offset.z + px.x;

    let uv = (vec2<f32>(px) + 0.5) / view.size.xy * 2.0;
    let rd = normalize(view.forward.xyz + view.right.xyz * (uv.x - 1.0) + view.up.xyz * (1.0 - uv.y));
    let ro = view.eye.xyz;
    let pixel = view.size.z;

    // The point is advanced with the step (p += rd·d), as sdfc does, rather than recomputed
    // from ro + rd·t: the same evaluations to the last bit of t on grazing rays.
    var p = ro;
    var t = 0.0;
    var steps = 0u;
    var hit = false;
    loop {
        if (steps >= STEPS) {
            break;
        }
        let d = map(p);
        steps += 1u;
        if (d < max(pixel * t, EPS_FLOOR)) {
            hit = true;
            break;
        }
        t += d;
        p += rd * d;
        if (t > MAX_T) {
            break;
        }
    }

    out[index] = vec2<u32>(bitcast<u32>(t), steps | (select(0u, 1u, hit) << 31u));
}
