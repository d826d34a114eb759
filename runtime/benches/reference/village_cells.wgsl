// village_cells.wgsl — hand-written reference for examples/village.sdf, written for
// `sdfc bench --reference` so that sdfc's generated shader can be timed against what a person
// would write by hand (Shadertoy style: one map(), each `repeat` as the one copy in the
// point's own cell, found by a clamped round(), the mirror as an abs() fold, constants folded by hand, no generic machinery).
//
// Scene: the village of Bálint & Valasek (2018), Fig. 4 (right): two rows of five gabled
// houses, a row of three town houses, two rows of three flat-roofed blocks, a church with a
// tower and spire turned 90° about y, eight trees on each side of the road (mirrored across
// z = 0), the road slab and the ground plane y = 0.
//
// `repeat((s), (n)) { shape } at c` puts n copies per axis centred on c: offsets
// (k − (n − 1)/2)·s, k = 0 … n − 1. So:
//   houses     x ∈ {−7, −4, −1, 2, 5},   z ∈ {−5.6, −2.4}           (3 × 3.2 around (−1, 0, −4))
//   townhouses x ∈ {−6.8, −3.5, −0.2},   z = 2.6                    (3.3 around (−3.5, 0, 2.6))
//   blocks     x ∈ {−7.4, −3.6, 0.2},    z ∈ {4.7, 8.5}             (3.8 × 3.8 around (−3.6, 0, 6.6))
//   trees      x ∈ {−6.45, −4.55, −2.65, −0.75, 1.15, 3.05, 4.95, 6.85}, z = ±1.05
//                                                                   (1.9 around (0.2, 0, 1.05), mirror(z))
// sdfc evaluates the copies that can be nearest (3 houses per row, because it cannot tell that
// the house with its 45°-turned roof is mirror-symmetric); here only the own cell's copy, as a
// person who knows the shapes are centred and symmetric in their cells writes it: the same
// field as the min over all copies (village.wgsl writes every copy out).
//
// Tracer: basic sphere tracing (Hart), as `sdfc ... --tracers basic --steps 200`:
//   steps 200, epsilon pixel: ε(t) = max(view.size.z · t, 2.0995714e-4) (the floor is
//   1e-5 · |eye − target|), max_distance 80. Per step: budget test, one map(), hit if d < ε(t)
//   (ε at the t before the step), t += d, stop when t > 80. The scene's own tracer is
//   `enhanced`; the benchmark compares the basic tracer.
//
// No hit confirmation: every part's field is a distance (the town-house roof is an exact box;
// an earlier version, with the roof stretched by a scale, confirmed hits as sdfc then did).
//
// Output: out[i] = (bitcast(t), steps | hit << 31), t where the ray stopped.

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

fn houses(p: vec3<f32>) -> f32 {
    let cx = clamp(round((p.x + 1.0) / 3.0), -2.0, 2.0) * 3.0 - 1.0;
    let cz = select(-5.6, -2.4, p.z > -4.0);
    return house(p - vec3<f32>(cx, 0.0, cz));
}

// (walls, roof, annex), each the nearest over the three town houses.
fn townhouses(p: vec3<f32>) -> vec3<f32> {
    let cx = clamp(round((p.x + 3.5) / 3.3), -1.0, 1.0) * 3.3 - 3.5;
    return townhouse(p - vec3<f32>(cx, 0.0, 2.6));
}

// Everything else: blocks, church, trees, road, ground.
fn rest(p: vec3<f32>) -> f32 {
    let bx = clamp(round((p.x + 3.6) / 3.8), -1.0, 1.0) * 3.8 - 3.6;
    let bz = select(4.7, 8.5, p.z > 6.6);
    var d = block(p - vec3<f32>(bx, 0.0, bz));

    // Church at (4.3, 0, 5.2), turned 90° about y: local (x, y, z) = (5.2 − pz, py, px − 4.3).
    let c = vec3<f32>(5.2 - p.z, p.y, p.x - 4.3);
    d = min(d, box3(c - vec3<f32>(0.0, 0.8, 0.0), vec3<f32>(0.8, 0.8, 1.6)));
    let r = c - vec3<f32>(0.0, 1.6, 0.0);
    d = min(d, box3(vec3<f32>(C45 * (r.x + r.y), C45 * (r.y - r.x), r.z), vec3<f32>(0.6, 0.6, 1.65)));
    d = min(d, box3(c - vec3<f32>(0.0, 1.7, -2.0), vec3<f32>(0.5, 1.7, 0.5)));
    d = min(d, cone(c - vec3<f32>(0.0, 4.3, -2.0), 0.72, 0.9, 0.26607067));

    // Trees on both sides of the road: fold z onto z > 0.
    let m = vec3<f32>(p.x, p.y, abs(p.z) - 1.05);
    let tx = clamp(round((p.x - 0.2) / 1.9 + 3.5), 0.0, 7.0) * 1.9 - 6.45;
    d = min(d, tree(m - vec3<f32>(tx, 0.0, 0.0)));

    // Road and ground.
    d = min(d, box3(p, vec3<f32>(11.0, 0.02, 0.65)));
    return min(d, p.y);
}

fn map(p: vec3<f32>) -> f32 {
    let t = townhouses(p);
    return min(min(houses(p), rest(p)), min(min(t.x, t.y), t.z));
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
