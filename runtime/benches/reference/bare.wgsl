// bare.wgsl — a bare dispatch: the trace-only interface (runtime/benches/reference/README.md)
// with no tracing at all. Every pixel writes t = 0 and 0 steps, not hit. Timed next to sdfc's
// trace-only module on a trivial scene, it shows bench's fixed cost per frame
// (`sdfc bench examples/bench/trivial.sdf --reference runtime/benches/reference/bare.wgsl`).

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

@compute @workgroup_size(8, 8, 1)
fn main(@builtin(global_invocation_id) gid: vec3<u32>) {
    let p = gid.xy + view.offset.xy;
    if (p.x >= view.offset.z || p.y >= view.offset.w) {
        return;
    }
    out[p.y * view.offset.z + p.x] = vec2<u32>(0u, 0u);
}
