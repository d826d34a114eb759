// Written by sdfc (`sdfc emit --entry shadertoy`): paste into Shadertoy's Image tab.
// Drag with the mouse to turn the camera around its target.


struct Params {
    float height;
    float reach;
    float nod;
    float glow;
    float spread;
    float time;
};
struct TraceResult {
    float t;
    uint steps;
    uint flags;
};
const uint MATERIAL_brass = 1u;
const uint MATERIAL_shade = 2u;
const uint MATERIAL_bulb = 3u;
const uint MATERIAL_desk = 4u;

Params params = Params(0.0, 0.0, 0.0, 0.0, 0.0, 0.0);


float sd_sphere(vec3 p, float radius) {
    return (length(p) - radius);
}

float sd_cone(vec3 p_1, float radius_1, float height, float top) {
    float _e5 = (height * 0.5);
    float _e7 = length(p_1.xz);
    vec2 _e9 = vec2(_e7, p_1.y);
    vec2 _e10 = vec2(top, _e5);
    float _e13 = (_e5 * 2.0);
    vec2 _e14 = vec2((top - radius_1), _e13);
    float _e21 = (abs(p_1.y) - _e5);
    vec2 _e22 = vec2((_e7 - min(_e7, ((p_1.y < 0.0) ? radius_1 : top))), _e21);
    vec2 _e33 = ((_e9 - _e10) + (_e14 * clamp((dot((_e10 - _e9), _e14) / max(dot(_e14, _e14), 1e-30)), 0.0, 1.0)));
    return ((((((_e13 * (_e7 - top)) + ((radius_1 - top) * (p_1.y - _e5))) < 0.0) && (_e21 < 0.0)) ? -1.0 : 1.0) * sqrt(min(dot(_e22, _e22), dot(_e33, _e33))));
}

float sd_cylinder(vec3 p_2, float radius_2, float height_1) {
    vec2 _e11 = (abs(vec2(length(p_2.xz), p_2.y)) - vec2(radius_2, (height_1 * 0.5)));
    return (min(max(_e11.x, _e11.y), 0.0) + length(max(_e11, vec2(0.0))));
}

float sd_capsule(vec3 p_3, float height_2, float radius_3) {
    float _e4 = (height_2 * 0.5);
    return (length(vec3(p_3.x, (p_3.y - clamp(p_3.y, -(_e4), _e4)), p_3.z)) - radius_3);
}

float sd_box(vec3 p_4, vec3 size) {
    vec3 _e5 = (abs(p_4) - (size * 0.5));
    return (length(max(_e5, vec3(0.0))) + min(max(_e5.x, max(_e5.y, _e5.z)), 0.0));
}

float let_joint(vec3 p_5) {
    float _e2 = sd_sphere(p_5, 0.09);
    return _e2;
}

float let_head(vec3 p_6) {
    float _e3 = params.spread;
    float _e6 = sd_cone(p_6, _e3, 0.45, 0.08);
    float _e14 = params.spread;
    float _e19 = sd_cone((p_6 - vec3(0.0, -0.04, 0.0)), (_e14 - 0.08), 0.49, 0.02);
    float _e29 = params.glow;
    float _e30 = sd_sphere((p_6 - vec3(0.0, -0.2, 0.0)), _e29);
    return min(max(_e6, -(_e19)), _e30);
}

float map(vec3 p_7) {
    float _e8 = sd_cylinder((p_7 - vec3(0.0, 0.04, 0.0)), 0.6, 0.08);
    float _e16 = sd_capsule((p_7 - vec3(0.0, 0.6, 0.0)), 1.0, 0.05);
    float d = min(_e8, _e16);
    float _e23 = let_joint((p_7 - vec3(0.0, 1.1, 0.0)));
    float d_1 = min(d, _e23);
    vec3 _e29 = (p_7 - vec3(0.0, 1.1, 0.0));
    float _e32 = params.reach;
    float _e33 = -(_e32);
    float _e34 = sin(_e33);
    float _e35 = cos(_e33);
    vec3 _e45 = vec3(((_e35 * _e29.x) - (_e34 * _e29.y)), ((_e34 * _e29.x) + (_e35 * _e29.y)), _e29.z);
    float _e49 = params.height;
    float _e57 = params.height;
    float _e59 = sd_capsule((_e45 - vec3(0.0, (_e49 / 2.0), 0.0)), _e57, 0.045);
    float _e63 = params.height;
    float _e67 = let_joint((_e45 - vec3(0.0, _e63, 0.0)));
    float d_2 = min(_e59, _e67);
    float _e72 = params.height;
    vec3 _e75 = (_e45 - vec3(0.0, _e72, 0.0));
    float _e78 = params.nod;
    float _e81 = params.time;
    float _e85 = -((_e78 + (_e81 * 0.2617994)));
    float _e86 = sin(_e85);
    float _e87 = cos(_e85);
    float _e98 = let_head(vec3(_e75.x, ((_e87 * _e75.y) - (_e86 * _e75.z)), ((_e86 * _e75.y) + (_e87 * _e75.z))));
    float _e110 = sd_box((p_7 - vec3(0.0, -0.1, 0.0)), vec3(5.0, 0.2, 3.0));
    return min(min(d_1, min(d_2, _e98)), _e110);
}

uint map_material(vec3 p_8) {
    float _e8 = sd_cylinder((p_8 - vec3(0.0, 0.04, 0.0)), 0.6, 0.08);
    float _e17 = sd_capsule((p_8 - vec3(0.0, 0.6, 0.0)), 1.0, 0.05);
    float d_3 = min(_e8, _e17);
    float _e25 = let_joint((p_8 - vec3(0.0, 1.1, 0.0)));
    float d_4 = min(d_3, _e25);
    vec3 _e32 = (p_8 - vec3(0.0, 1.1, 0.0));
    float _e35 = params.reach;
    float _e36 = -(_e35);
    float _e37 = sin(_e36);
    float _e38 = cos(_e36);
    vec3 _e48 = vec3(((_e38 * _e32.x) - (_e37 * _e32.y)), ((_e37 * _e32.x) + (_e38 * _e32.y)), _e32.z);
    float _e52 = params.height;
    float _e60 = params.height;
    float _e62 = sd_capsule((_e48 - vec3(0.0, (_e52 / 2.0), 0.0)), _e60, 0.045);
    float _e67 = params.height;
    float _e71 = let_joint((_e48 - vec3(0.0, _e67, 0.0)));
    float d_5 = min(_e62, _e71);
    float _e77 = params.height;
    vec3 _e80 = (_e48 - vec3(0.0, _e77, 0.0));
    float _e83 = params.nod;
    float _e86 = params.time;
    float _e90 = -((_e83 + (_e86 * 0.2617994)));
    float _e91 = sin(_e90);
    float _e92 = cos(_e90);
    vec3 _e102 = vec3(_e80.x, ((_e92 * _e80.y) - (_e91 * _e80.z)), ((_e91 * _e80.y) + (_e92 * _e80.z)));
    float _e105 = params.spread;
    float _e108 = sd_cone(_e102, _e105, 0.45, 0.08);
    float _e117 = params.spread;
    float _e122 = sd_cone((_e102 - vec3(0.0, -0.04, 0.0)), (_e117 - 0.08), 0.49, 0.02);
    float _e124 = max(_e108, -(_e122));
    float _e137 = params.glow;
    float _e138 = sd_sphere((_e102 - vec3(0.0, -0.2, 0.0)), _e137);
    float _e140 = min(_e124, _e138);
    float _e143 = min(d_5, _e140);
    bool _e144 = (_e71 < _e62);
    bool _e150 = (_e17 < _e8);
    float _e152 = (_e150 ? _e17 : _e8);
    bool _e153 = (_e25 < _e152);
    float _e167 = sd_box((p_8 - vec3(0.0, -0.1, 0.0)), vec3(5.0, 0.2, 3.0));
    return ((_e167 < min(d_4, _e143)) ? 4u : ((_e143 < (_e153 ? _e25 : _e152)) ? ((_e140 < (_e144 ? _e71 : _e62)) ? ((_e138 < _e124) ? 3u : (((_e122 * -1.0) > _e108) ? 0u : 2u)) : (_e144 ? 1u : 1u)) : (_e153 ? 1u : (_e150 ? 1u : 1u))));
}

vec3 map_texture(vec3 p_9) {
    float _e8 = sd_cylinder((p_9 - vec3(0.0, 0.04, 0.0)), 0.6, 0.08);
    float _e21 = sd_capsule((p_9 - vec3(0.0, 0.6, 0.0)), 1.0, 0.05);
    float d_6 = min(_e8, _e21);
    vec3 _e32 = (p_9 - vec3(0.0, 1.1, 0.0));
    float _e33 = let_joint(_e32);
    float d_7 = min(d_6, _e33);
    vec3 _e44 = (p_9 - vec3(0.0, 1.1, 0.0));
    float _e47 = params.reach;
    float _e48 = -(_e47);
    float _e49 = sin(_e48);
    float _e50 = cos(_e48);
    vec3 _e60 = vec3(((_e50 * _e44.x) - (_e49 * _e44.y)), ((_e49 * _e44.x) + (_e50 * _e44.y)), _e44.z);
    float _e64 = params.height;
    float _e72 = params.height;
    float _e74 = sd_capsule((_e60 - vec3(0.0, (_e64 / 2.0), 0.0)), _e72, 0.045);
    float _e83 = params.height;
    vec3 _e86 = (_e60 - vec3(0.0, _e83, 0.0));
    float _e87 = let_joint(_e86);
    float d_8 = min(_e74, _e87);
    float _e97 = params.height;
    vec3 _e100 = (_e60 - vec3(0.0, _e97, 0.0));
    float _e103 = params.nod;
    float _e106 = params.time;
    float _e110 = -((_e103 + (_e106 * 0.2617994)));
    float _e111 = sin(_e110);
    float _e112 = cos(_e110);
    vec3 _e122 = vec3(_e100.x, ((_e112 * _e100.y) - (_e111 * _e100.z)), ((_e111 * _e100.y) + (_e112 * _e100.z)));
    float _e125 = params.spread;
    float _e128 = sd_cone(_e122, _e125, 0.45, 0.08);
    float _e141 = params.spread;
    float _e146 = sd_cone((_e122 - vec3(0.0, -0.04, 0.0)), (_e141 - 0.08), 0.49, 0.02);
    float _e148 = max(_e128, -(_e146));
    float _e162 = params.glow;
    float _e163 = sd_sphere((_e122 - vec3(0.0, -0.2, 0.0)), _e162);
    float _e169 = min(_e148, _e163);
    float _e172 = min(d_8, _e169);
    bool _e173 = (_e87 < _e74);
    bool _e179 = (_e21 < _e8);
    float _e181 = (_e179 ? _e21 : _e8);
    bool _e182 = (_e33 < _e181);
    float _e196 = sd_box((p_9 - vec3(0.0, -0.1, 0.0)), vec3(5.0, 0.2, 3.0));
    vec4 _e203 = ((_e196 < min(d_7, _e172)) ? vec4(p_9.x, p_9.y, p_9.z, 1.0) : ((_e172 < (_e182 ? _e33 : _e181)) ? ((_e169 < (_e173 ? _e87 : _e74)) ? ((_e163 < _e148) ? vec4(_e122.x, _e122.y, _e122.z, 1.0) : (((_e146 * -1.0) > _e128) ? vec4(0.0, 0.0, 0.0, 0.0) : vec4(_e122.x, _e122.y, _e122.z, 1.0))) : (_e173 ? vec4(_e86.x, _e86.y, _e86.z, 1.0) : vec4(_e60.x, _e60.y, _e60.z, 1.0))) : (_e182 ? vec4(_e32.x, _e32.y, _e32.z, 1.0) : (_e179 ? vec4(p_9.x, p_9.y, p_9.z, 1.0) : vec4(p_9.x, p_9.y, p_9.z, 1.0)))));
    return ((_e203.w > 0.0) ? _e203.xyz : p_9);
}

TraceResult trace_basic(vec3 ro, vec3 rd, float pixel) {
    float t = 0.0;
    uint steps = 0u;
    uint flags = 0u;
    vec3 position = vec3(0.0);
    t = 0.0;
    steps = 0u;
    flags = 0u;
    position = ro;
    while(true) {
        uint _e9 = steps;
        if ((_e9 >= 128u)) {
            flags = 2u;
            break;
        }
        float _e13 = t;
        vec3 _e14 = position;
        float _e15 = map(_e14);
        uint _e16 = steps;
        steps = (_e16 + 1u);
        if ((_e15 < max((pixel * _e13), 6.744627e-5))) {
            flags = 1u;
            break;
        }
        float _e24 = (_e13 + _e15);
        t = _e24;
        vec3 _e25 = position;
        position = (_e25 + (rd * _e15));
        if ((_e24 > 100.0)) {
            break;
        }
    }
    float _e30 = t;
    uint _e31 = steps;
    uint _e32 = flags;
    return TraceResult(_e30, _e31, _e32);
}

vec3 normal(vec3 p_10, float h) {
    vec3 gradient = vec3(0.0);
    uint corner = 0u;
    gradient = vec3(0.0);
    corner = 0u;
    while(true) {
        uint _e10 = corner;
        if ((_e10 >= 4u)) {
            break;
        }
        vec3 _e32 = ((vec3(float((((_e10 + 3u) >> 1u) & 1u)), float(((_e10 >> 1u) & 1u)), float((_e10 & 1u))) * 2.0) - vec3(1.0));
        float _e35 = map((p_10 + (_e32 * (h * 0.57735026))));
        vec3 _e37 = gradient;
        gradient = (_e37 + (_e32 * _e35));
        corner = (_e10 + 1u);
    }
    vec3 _e41 = gradient;
    float _e42 = length(_e41);
    return ((_e42 > 1e-30) ? (_e41 * (1.0 / _e42)) : vec3(0.0));
}

float lattice_hash(ivec3 i) {
    uvec3 _e1 = uvec3(i);
    uint _e12 = (((_e1.x * 2376512323u) ^ (_e1.y * 3625334849u)) ^ (_e1.z * 3407524639u));
    uint _e17 = ((_e12 ^ (_e12 >> 16u)) * 2146121005u);
    uint _e22 = ((_e17 ^ (_e17 >> 15u)) * 2221713035u);
    return (float(((_e22 ^ (_e22 >> 16u)) >> 8u)) * 5.9604645e-8);
}

float value_noise(vec3 q) {
    vec3 _e1 = floor(q);
    vec3 _e2 = (q - _e1);
    vec3 _e10 = ((_e2 * _e2) * (vec3(3.0) - (vec3(2.0) * _e2)));
    ivec3 _e19 = ivec3((_e1 - (vec3(65536.0) * floor((_e1 * vec3(1.5258789e-5))))));
    float _e28 = lattice_hash((_e19 + ivec3(0, 0, 0)));
    float _e34 = lattice_hash((_e19 + ivec3(1, 0, 0)));
    float _e40 = lattice_hash((_e19 + ivec3(0, 1, 0)));
    float _e46 = lattice_hash((_e19 + ivec3(1, 1, 0)));
    float _e52 = lattice_hash((_e19 + ivec3(0, 0, 1)));
    float _e58 = lattice_hash((_e19 + ivec3(1, 0, 1)));
    float _e64 = lattice_hash((_e19 + ivec3(0, 1, 1)));
    float _e70 = lattice_hash((_e19 + ivec3(1, 1, 1)));
    float _e73 = (_e28 + ((_e34 - _e28) * _e10.x));
    float _e79 = (_e52 + ((_e58 - _e52) * _e10.x));
    float _e85 = (_e73 + (((_e40 + ((_e46 - _e40) * _e10.x)) - _e73) * _e10.y));
    return (_e85 + (((_e79 + (((_e64 + ((_e70 - _e64) * _e10.x)) - _e79) * _e10.y)) - _e85) * _e10.z));
}

float shadow(vec3 p_11, vec3 n, vec3 l, float far, float h_1, float k) {
    float t_1 = 0.0;
    float lit = 0.0;
    uint i_1 = 0u;
    float _e6 = map(p_11);
    t_1 = 0.0;
    lit = 1.0;
    i_1 = 0u;
    while(true) {
        float _e19 = t_1;
        uint _e20 = i_1;
        if (((_e20 >= 64u) || (_e19 >= far))) {
            break;
        }
        uint _e25 = i_1;
        i_1 = (_e25 + 1u);
        float _e30 = map(((p_11 + (n * (max(abs(_e6), h_1) * 2.0))) + (l * _e19)));
        if ((_e30 < h_1)) {
            lit = 0.0;
            break;
        }
        float _e39 = lit;
        lit = ((k > 0.0) ? min(_e39, ((k * _e30) / max(_e19, 1e-6))) : _e39);
        t_1 = (_e19 + _e30);
    }
    float _e43 = lit;
    return clamp(_e43, 0.0, 1.0);
}

vec3 shade(vec3 p_12, vec3 n_1, vec3 rd_1, uint material, float h_2) {
    vec3 _e4 = map_texture(p_12);
    vec3 _e6 = (_e4 * 8.333333);
    float _e16 = value_noise((_e6 * 1.0));
    float _e21 = value_noise((_e6 * 2.0));
    float _e27 = value_noise((_e6 * 4.0));
    bool _e55 = (material == 1u);
    bool _e65 = (material == 2u);
    bool _e74 = (material == 3u);
    bool _e83 = (material == 4u);
    vec3 _e84 = (_e83 ? mix(vec3(0.3515326, 0.16202937, 0.045186203), vec3(0.14412847, 0.059511237, 0.019382361), vec3((0.5 + (0.5 * sin((6.2831855 * ((sqrt(((_e4.x * _e4.x) + (_e4.z * _e4.z))) * 8.333333) + (0.4 * ((((1.0 * _e16) + (0.5 * _e21)) + (0.25 * _e27)) * 0.5714286))))))))) : (_e74 ? vec3(1.0, 0.8879231, 0.5271151) : (_e65 ? vec3(0.02842604, 0.114435375, 0.2746773) : (_e55 ? vec3(0.57758045, 0.3515326, 0.08021982) : vec3(0.60382736)))));
    float _e86 = (_e83 ? 0.0 : (_e74 ? 0.0 : (_e65 ? 0.3 : (_e55 ? 0.6 : 0.0))));
    vec3 _e92 = vec3(-0.42107597, 0.84215194, -0.33686078);
    float _e101 = shadow(p_12, n_1, _e92, 100.0, h_2, 8.0);
    vec3 _e102 = (vec3(1.0) * _e101);
    vec3 _e106 = (_e92 - rd_1);
    vec3 _e125 = (vec3(1.5, 3.5, -2.0) - p_12);
    vec3 _e132 = ((dot(_e125, _e125) == 0.0) ? vec3(0.0) : normalize(_e125));
    vec3 _e139 = vec3(0.6, 0.41632307, 0.21091956);
    vec3 _e143 = (_e132 - rd_1);
    return (((((_e84 * 0.12) + (_e84 * (_e102 * max(dot(n_1, _e92), 0.0)))) + (_e102 * (pow(max(dot(n_1, ((dot(_e106, _e106) == 0.0) ? vec3(0.0) : normalize(_e106))), 0.0), 32.0) * _e86))) + (_e84 * (_e139 * max(dot(n_1, _e132), 0.0)))) + (_e139 * (pow(max(dot(n_1, ((dot(_e143, _e143) == 0.0) ? vec3(0.0) : normalize(_e143))), 0.0), 32.0) * _e86)));
}

TraceResult trace(vec3 ro_1, vec3 rd_2, float pixel_1) {
    TraceResult _e3 = trace_basic(ro_1, rd_2, pixel_1);
    return _e3;
}

vec4 color(vec3 ro_2, vec3 rd_3, float pixel_2) {
    vec3 color_1 = vec3(0.0);
    vec3 n_2 = vec3(0.0);
    uint material_1 = 0u;
    TraceResult _e3 = trace_basic(ro_2, rd_3, pixel_2);
    color_1 = vec3(0.011612245, 0.014443844, 0.02121901);
    n_2 = vec3(0.0);
    material_1 = 0u;
    if (((_e3.flags & 1u) != 0u)) {
        vec3 _e21 = (ro_2 + (rd_3 * _e3.t));
        float _e24 = max((pixel_2 * _e3.t), 6.744627e-5);
        vec3 _e25 = normal(_e21, _e24);
        uint _e26 = map_material(_e21);
        vec3 _e27 = shade(_e21, _e25, rd_3, _e26, _e24);
        n_2 = _e25;
        material_1 = _e26;
        color_1 = _e27;
    }
    vec3 _e28 = color_1;
    return vec4(_e28.x, _e28.y, _e28.z, (((_e3.flags & 1u) != 0u) ? 1.0 : 0.0));
}



void mainImage(out vec4 fragColor, in vec2 fragCoord) {
    params = Params(1.3, 0.5235988, 0.34906584, 0.16, 0.35, iTime);
    vec3 target = vec3(0.0, 1.2, 0.0);
    vec3 offset = vec3(2.5, 3.0, -6.0) - target;
    float r = length(offset);
    vec3 eye = vec3(2.5, 3.0, -6.0);
    if (iMouse.z > 0.0) {
        float yaw = (iMouse.x / iResolution.x - 0.5) * 6.2831853;
        float pitch = (iMouse.y / iResolution.y - 0.5) * 3.0;
        float azimuth = atan(offset.x, offset.z) + yaw;
        float elevation = clamp(asin(offset.y / r) + pitch, -1.5, 1.5);
        eye = target + r * vec3(cos(elevation) * sin(azimuth), sin(elevation), cos(elevation) * cos(azimuth));
    }
    vec3 forward = normalize(target - eye);
    vec3 right = normalize(cross(forward, vec3(0.0, 1.0, 0.0)));
    vec3 up = cross(right, forward);
    float t = 0.41421357;
    // The ray of `sdfc render`'s camera (docs/interface.md); fragCoord's y grows upwards.
    vec2 uv = 2.0 * fragCoord / iResolution.xy - 1.0;
    vec3 rd = normalize(forward + right * (t * iResolution.x / iResolution.y) * uv.x + up * t * uv.y);
    vec4 c = color(eye, rd, t / iResolution.y);
    vec3 lin = clamp(c.rgb, 0.0, 1.0);
    vec3 srgb = mix(lin * 12.92, 1.055 * pow(lin, vec3(1.0 / 2.4)) - 0.055, step(0.0031308, lin));
    fragColor = vec4(srgb, 1.0);
}
