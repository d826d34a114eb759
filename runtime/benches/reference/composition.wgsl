// composition.wgsl — hand-written reference for examples/composition.sdf, written for
// `sdfc bench --reference` so that sdfc's generated shader can be timed against what a person
// would write by hand (Shadertoy style: one flat map(), every part written out, constants
// folded by hand, no generic machinery).
//
// Scene: the still life of Bálint & Valasek (2018), Fig. 4 (middle): a red torus on edge around
// a white ball on a stand, a stack of two boxes and a ball, a pillar with two rings and a ball,
// a drilled block, a lying cylinder, a flat torus, a mirrored colonnade of six cylinders capped
// by boxes, and the floor plane y = 0.
//
// Tracer: basic sphere tracing (Hart), as `sdfc ... --tracers basic --steps 160`:
//   steps 160, epsilon pixel: ε(t) = max(view.size.z · t, 8.443488e-5) (the floor is
//   1e-5 · |eye − target|), max_distance 60. Per step: budget test, one map(), hit if d < ε(t)
//   (ε at the t before the step), t += d, stop when t > 60. The scene's own tracer is
//   `enhanced`; the benchmark compares the basic tracer.
// Every field is exact (no loose part), so there is no hit confirmation.
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

const STEPS: u32 = 160u;
const EPS_FLOOR: f32 = 0.00008443488;
const MAX_T: f32 = 60.0;

// b: half extents.
fn box3(p: vec3<f32>, b: vec3<f32>) -> f32 {
    let q = abs(p) - b;
    return length(max(q, vec3<f32>(0.0))) + min(max(q.x, max(q.y, q.z)), 0.0);
}

// Capped cylinder around y: radius r, half height h.
fn cyl_y(p: vec3<f32>, r: f32, h: f32) -> f32 {
    let d = abs(vec2<f32>(length(p.xz), p.y)) - vec2<f32>(r, h);
    return min(max(d.x, d.y), 0.0) + length(max(d, vec2<f32>(0.0)));
}

// Torus in the xz plane.
fn torus_y(p: vec3<f32>, R: f32, r: f32) -> f32 {
    return length(vec2<f32>(length(p.xz) - R, p.y)) - r;
}

fn map(p: vec3<f32>) -> f32 {
    // Ring on edge (its axis along z) around a ball on a stand.
    let c = p - vec3<f32>(0.0, 1.15, 0.5);
    var d = length(vec2<f32>(length(c.xy) - 0.9, c.z)) - 0.22;
    d = min(d, length(c) - 0.42);
    d = min(d, cyl_y(p - vec3<f32>(0.0, 0.25, 0.5), 0.12, 0.25));

    // Stack: a unit box, a box turned 30° about y, a ball.
    d = min(d, box3(p - vec3<f32>(-2.3, 0.5, 0.4), vec3<f32>(0.5)));
    let s = p - vec3<f32>(-2.3, 1.3, 0.4);
    let sr = vec3<f32>(0.8660254 * s.x - 0.5 * s.z, s.y, 0.5 * s.x + 0.8660254 * s.z);
    d = min(d, box3(sr, vec3<f32>(0.375, 0.3, 0.375)));
    d = min(d, length(p - vec3<f32>(-2.3, 1.9, 0.4)) - 0.3);

    // Pillar with two rings and a ball.
    d = min(d, cyl_y(p - vec3<f32>(2.3, 0.85, 0.5), 0.3, 0.85));
    d = min(d, torus_y(p - vec3<f32>(2.3, 0.12, 0.5), 0.55, 0.12));
    d = min(d, torus_y(p - vec3<f32>(2.3, 0.9, 0.5), 0.45, 0.1));
    d = min(d, length(p - vec3<f32>(2.3, 2.1, 0.5)) - 0.42);

    // Block turned −20° about y, drilled along its local z.
    let b = p - vec3<f32>(-1.1, 0.3, -1.1);
    let br = vec3<f32>(0.9396926 * b.x + 0.34202015 * b.z, b.y, 0.9396926 * b.z - 0.34202015 * b.x);
    let hole = abs(vec2<f32>(length(br.xy), br.z)) - vec2<f32>(0.2, 1.0);
    let drill = min(max(hole.x, hole.y), 0.0) + length(max(hole, vec2<f32>(0.0)));
    d = min(d, max(box3(br, vec3<f32>(0.45, 0.3, 0.3)), -drill));

    // Lying cylinder: axis along x, then turned 25° about y.
    let l = p - vec3<f32>(1.1, 0.22, -1.2);
    let lr = vec3<f32>(0.9063078 * l.x - 0.42261827 * l.z, l.y, 0.42261827 * l.x + 0.9063078 * l.z);
    let lc = abs(vec2<f32>(length(lr.yz), lr.x)) - vec2<f32>(0.22, 0.55);
    d = min(d, min(max(lc.x, lc.y), 0.0) + length(max(lc, vec2<f32>(0.0))));

    // Flat torus.
    d = min(d, torus_y(p - vec3<f32>(0.2, 0.09, -1.6), 0.3, 0.09));

    // Colonnade at z = 2.9, mirrored across x = 0: three columns and caps on the +x side.
    let m = vec3<f32>(abs(p.x), p.y, p.z - 2.9);
    d = min(d, cyl_y(m - vec3<f32>(0.65, 1.2, 0.0), 0.2, 1.2));
    d = min(d, box3(m - vec3<f32>(0.65, 2.48, 0.0), vec3<f32>(0.25, 0.08, 0.25)));
    d = min(d, cyl_y(m - vec3<f32>(1.95, 1.2, 0.0), 0.2, 1.2));
    d = min(d, box3(m - vec3<f32>(1.95, 2.48, 0.0), vec3<f32>(0.25, 0.08, 0.25)));
    d = min(d, cyl_y(m - vec3<f32>(3.25, 1.2, 0.0), 0.2, 1.2));
    d = min(d, box3(m - vec3<f32>(3.25, 2.48, 0.0), vec3<f32>(0.25, 0.08, 0.25)));

    // Floor.
    return min(d, p.y);
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
    var hit = 0u;
    loop {
        if (steps >= STEPS) {
            break;
        }
        let d = map(p);
        steps += 1u;
        if (d < max(pixel * t, EPS_FLOOR)) {
            hit = 1u;
            break;
        }
        t += d;
        p += rd * d;
        if (t > MAX_T) {
            break;
        }
    }
    out[index] = vec2<u32>(bitcast<u32>(t), steps | (hit << 31u));
}
