// `photon-trace`, beyond the papers: photons traced exactly through every triangle of the scene
// on the GPU, with the physics of the CPU reference (`crates/caustics/src/reference`), into the
// photon buffer that the caustic map's deposit stages splat like every other technique's. The
// surface a photon meets next is found by the BVH's traversal in this shader, or with RAY_QUERY by
// a ray query against the Vulkan acceleration structures (`trace`).
//
// Emission: light l sends side² photons uniformly in solid angle over the cone from it that
// subtends the specular objects' bounding sphere (the reference's cone per object, made one);
// photon (i, j) is jittered inside stratum (i, j) of the (1 - cos, azimuth) square (at its
// centre with PHOTON_TRACE_CENTRED, `jitter = false`), so the
// cone's solid angle Omega is split evenly and each photon carries I(w) Omega / side² (I the
// light's radiant intensity towards w, spot cone and texture applied), the photon buffer's
// power per photon. Seeded: the same seed gives the same photons, frame after frame.
//
// Transport, as `reference::tracer`: at a refractive surface exact Snell about the smooth
// (interpolated) normal with the material's IOR (one RGB channel per photon, picked at random
// and its power tripled, where a material's IORs differ); with Fresnel (settings.w
// CAUSTIC_FRESNEL) the photon reflects with probability F (Russian roulette, power unchanged),
// total internal reflection reflects, and with PHOTON_TRACE_OUTSIDE_REFLECTION off a photon
// reflected off a refractive object's outside is dropped; without Fresnel every photon is
// transmitted, a photon meeting total internal reflection is dropped, and after two refractions
// (or one mirror) it goes straight to the first diffuse surface, the image-space model. Mirrors
// reflect exactly, times their specular colour. The transmission colour applies on every exit.
// After `max_bounces` specular interactions a photon is dropped. It lands on the first diffuse
// surface it meets after at least one specular interaction; one whose first hit is diffuse (or
// nothing) is direct light, not a caustic photon, and carries nothing.
//
// GLSL 4.60: GL_EXT_ray_query needs it.
//
// DIFFERENTIALS (`differentials = true`): photon differentials (Schjøth, Frisvad, Erleben &
// Sporring 2007, after Igehy 1999's ray differentials). Each photon carries the derivatives of its
// position and direction with respect to the emission square's two coordinates, each times the
// stratum's side 1/N (so they span the photon's share of the square): at emission from the cone's
// parametrization, then through every transfer to a surface (Igehy Eq. 10-11), mirror reflection
// (Eq. 14-15) and refraction (Eq. 16-18), with the derivatives of the interpolated normal from
// the hit's barycentric derivatives. Where it lands, the position derivatives (its footprint)
// are written beside the photon buffer; photon_trace/differential_splat.comp splats the ellipse
// they span.
//
// RECEIVER_DEPOSIT (`deposit = "receiver-map"`): a photon that lands on the receiver rectangle
// (within `receiver_tolerance` of its plane) also adds its power to its receiver-map texel, as
// the reference bins it (`reference::receiver::Receiver::texel_of`).
#version 460
#ifdef RECEIVER_DEPOSIT
#extension GL_EXT_shader_atomic_float : require
#endif
#ifdef RAY_QUERY
#extension GL_EXT_ray_query : require
#endif
#define CAUSTICS_BINDING 1
#define SPOT_BINDING 2
#define TRIANGLES_BINDING 4
#include "common/caustics.glsl"
#include "common/spot_texture.glsl"
#include "common/fresnel.glsl"
#include "common/materials.glsl"
// RAY_QUERY (`trace = "ray-query"`): the driver's acceleration structures; else the BVH.
#ifdef RAY_QUERY
#define SCENE_BINDING 3
#include "photon_trace/ray_query.glsl"
#define scene_intersect ray_query_intersect
#else
#define NODES_BINDING 3
#include "photon_trace/bvh.glsl"
#define scene_intersect bvh_intersect
#endif
layout(local_size_x = 8, local_size_y = 8) in;
// Per triangle of `triangles`, the mesh's vertex normals at its three corners.
layout(std430, binding = 5) readonly buffer ShadingNormals { vec4 shading_normals[]; };
// Per object: its MATERIAL_*, IOR and colour (the transmission colour of a refractive object,
// the specular colour of a mirror).
struct SceneObject {
    uvec4 material;   // x: MATERIAL_*
    vec4 ior;         // rgb
    vec4 colour;      // rgb
};
layout(std430, binding = 6) readonly buffer Objects { SceneObject objects[]; };
layout(binding = 7, rgba32f) uniform writeonly image2D photon_position;
layout(binding = 8, rgba32f) uniform writeonly image2D photon_direction;
layout(binding = 9, rgba32f) uniform writeonly image2D photon_power;
#ifdef DIFFERENTIALS
layout(binding = 11, rgba32f) uniform writeonly image2D photon_footprint_u;
layout(binding = 12, rgba32f) uniform writeonly image2D photon_footprint_v;
#endif
#ifdef RECEIVER_DEPOSIT
// Per receiver-map texel: power (W, rgb) and photon count, zeroed before the frame's first light.
layout(std430, binding = 10) buffer ReceiverFlux { float receiver_flux[]; };
#endif

layout(push_constant) uniform PhotonTraceConstants {
    vec4 sphere;         // xyz centre, w radius: the specular objects' bounding sphere
    uint light;
    uint seed;
    uint max_bounces;
    uint flags;          // PHOTON_TRACE_*
    float eps;           // ray offset against self-intersection (world units), the reference's
    float receiver_tolerance;  // how far from the receiver plane a photon lands on it
} constants;

#define PHOTON_TRACE_OUTSIDE_REFLECTION 1u
#define PHOTON_TRACE_DISPERSIVE 2u
#define PHOTON_TRACE_CENTRED 4u   // each photon at its stratum's centre (`jitter = false`)
// Why a photon carries nothing (direction.w), as shared/trace_surface.glsl says it.
#define PHOTON_LOST_TIR 1.0
#define PHOTON_LOST_OTHER 3.0
// Specular surfaces passed through on the way to a diffuse one (the image-space model), at most.
#define MAX_SKIPS 256u

// PCG hash (Jarzynski & Olano 2020): a well-mixed 32-bit value of `v`.
uint pcg_hash(uint v) {
    uint state = v * 747796405u + 2891336453u;
    uint word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
    return (word >> 22u) ^ word;
}

// Uniform in [0, 1) from the photon's stream (`id`) and draw number `k`.
float random01(uint id, uint k) {
    uint h = pcg_hash(pcg_hash(pcg_hash(constants.seed) ^ id) + k * 0x9E3779B9u);
    return float(h >> 8) * (1.0 / 16777216.0);
}

// An orthonormal pair perpendicular to unit `n` (Duff et al. 2017).
void basis(vec3 n, out vec3 t, out vec3 b) {
    float s = n.z >= 0.0 ? 1.0 : -1.0;
    float a = -1.0 / (s + n.z);
    float c = n.x * n.y * a;
    t = vec3(1.0 + s * n.x * n.x * a, s * c, -s * n.x);
    b = vec3(c, s + n.y * n.y * a, -n.y);
}

// The normal photons scatter about at a hit: the interpolated vertex normal on the side of the
// geometric normal `ng` (the geometric one where they cancel).
vec3 scatter_normal(RayHit h, vec3 ng) {
    vec3 n = hit_to_world(h, shading_normals[3u * h.triangle].xyz * (1.0 - h.u - h.v)
        + shading_normals[3u * h.triangle + 1u].xyz * h.u + shading_normals[3u * h.triangle + 2u].xyz * h.v);
    float len = length(n);
    if (len == 0.0) return ng;
    n /= len;
    return dot(n, ng) < 0.0 ? -n : n;
}

#ifdef DIFFERENTIALS
// A photon's differentials: d/du and d/dv of its position and direction, each times 1/N.
struct Differentials {
    vec3 pu, pv, du, dv;
};

// Transfer to the plane through the hit with geometric normal `ng`, `t` along `d` (Igehy Eq.
// 10-11): the position derivatives move along the direction's and are projected onto the plane
// along `d`.
void transfer(inout Differentials x, vec3 d, float t, vec3 ng) {
    float dn = dot(d, ng);
    vec3 qu = x.pu + t * x.du;
    vec3 qv = x.pv + t * x.dv;
    if (dn == 0.0) {
        // Grazing: no projection onto the plane.
        x.pu = qu;
        x.pv = qv;
        return;
    }
    x.pu = qu - d * (dot(qu, ng) / dn);
    x.pv = qv - d * (dot(qv, ng) / dn);
}

// The derivative of the scatter normal (scatter_normal's: the interpolated vertex normal,
// normalized, on the side of `ng`) along the position derivative `dp`, from the barycentric
// coordinates' derivatives on the hit triangle.
vec3 normal_derivative(RayHit h, BvhTriangle tri, vec3 ng, vec3 dp) {
    vec3 e1 = hit_to_world(h, tri.e1);
    vec3 e2 = hit_to_world(h, tri.e2);
    vec3 n = cross(e1, e2);
    float nn = dot(n, n);
    if (nn == 0.0) return vec3(0.0);
    float db1 = dot(cross(dp, e2), n) / nn;
    float db2 = dot(cross(e1, dp), n) / nn;
    vec3 n0 = shading_normals[3u * h.triangle].xyz;
    vec3 n1 = shading_normals[3u * h.triangle + 1u].xyz;
    vec3 n2 = shading_normals[3u * h.triangle + 2u].xyz;
    vec3 ni = hit_to_world(h, n0 * (1.0 - h.u - h.v) + n1 * h.u + n2 * h.v);
    float len = length(ni);
    if (len == 0.0) return vec3(0.0);
    vec3 unit = ni / len;
    vec3 dni = hit_to_world(h, (n1 - n0) * db1 + (n2 - n0) * db2);
    vec3 dn = (dni - unit * dot(unit, dni)) / len;
    return dot(unit, ng) < 0.0 ? -dn : dn;
}

// Mirror reflection about unit `n` (Igehy Eq. 14-15): r = d - 2 (d.n) n.
vec3 reflected_derivative(vec3 d, vec3 n, vec3 dd, vec3 dn) {
    float dot_dn = dot(d, n);
    return dd - 2.0 * ((dot(dd, n) + dot(d, dn)) * n + dot_dn * dn);
}

// Refraction with relative index `eta` about unit `n` facing against `d` (Igehy Eq. 16-18; GLSL
// refract: t = eta d - (eta (n.d) + sqrt(k)) n, k = 1 - eta^2 (1 - (n.d)^2)).
vec3 refracted_derivative(vec3 d, vec3 n, float eta, vec3 dd, vec3 dn) {
    float nd = dot(n, d);
    float k = 1.0 - eta * eta * (1.0 - nd * nd);
    if (k <= 0.0) return vec3(0.0);
    float root = sqrt(k);
    float mu = -(eta * nd + root);
    float dnd = dot(dn, d) + dot(n, dd);
    float dmu = -eta * dnd * (1.0 + eta * nd / root);
    return eta * dd + dmu * n + mu * dn;
}

// The derivatives of a unit vector `v` kept tangent to it (what normalizing `v` does to them).
vec3 tangent(vec3 v, vec3 dv) {
    return dv - v * dot(v, dv);
}
#endif

void store(ivec2 texel, vec4 position, vec4 direction, vec4 power) {
    imageStore(photon_position, texel, position);
    imageStore(photon_direction, texel, direction);
    imageStore(photon_power, texel, power);
}

#ifdef RECEIVER_DEPOSIT
// Bins a photon landed at `p` with `power` into the receiver map, if it lies on its rectangle.
void deposit_on_receiver(vec3 p, vec3 power) {
    if (!(abs(p.y - frame.receiver.x) < constants.receiver_tolerance)) return;
    vec4 r = frame.receiver_range;
    vec2 f = vec2((p.x - r.x) / (r.y - r.x), (p.z - r.z) / (r.w - r.z));
    if (any(lessThan(f, vec2(0.0))) || any(greaterThanEqual(f, vec2(1.0)))) return;
    int n = int(frame.receiver.y);
    ivec2 ij = min(ivec2(f * float(n)), ivec2(n - 1));
    uint at = 4u * uint(ij.y * n + ij.x);
    atomicAdd(receiver_flux[at], power.r);
    atomicAdd(receiver_flux[at + 1u], power.g);
    atomicAdd(receiver_flux[at + 2u], power.b);
    atomicAdd(receiver_flux[at + 3u], 1.0);
}
#endif

void main() {
    ivec2 texel = ivec2(gl_GlobalInvocationID.xy);
    int side = imageSize(photon_position).x;
    if (texel.x >= side || texel.y >= side) return;
    uint l = constants.light;
    uint id = (l * uint(side) + uint(texel.y)) * uint(side) + uint(texel.x);
    vec3 light = frame.lights[l].position.xyz;
    vec3 to_centre = constants.sphere.xyz - light;
    float dist = length(to_centre);
    // The cone subtending the sphere; every direction from inside it.
    float cos_half = dist > constants.sphere.w ? sqrt(max(1.0 - pow(constants.sphere.w / dist, 2.0), 0.0)) : -1.0;
    vec3 axis = dist > constants.sphere.w ? to_centre / dist : vec3(0.0, 1.0, 0.0);
    vec3 t, b;
    basis(axis, t, b);
    bool centred = (constants.flags & PHOTON_TRACE_CENTRED) != 0u;
    float u1 = (float(texel.x) + (centred ? 0.5 : random01(id, 0u))) / float(side);
    float u2 = (float(texel.y) + (centred ? 0.5 : random01(id, 1u))) / float(side);
    float cos_t = 1.0 - u1 * (1.0 - cos_half);
    float sin_t = sqrt(max(1.0 - cos_t * cos_t, 0.0));
    float phi = 6.28318530717959 * u2;
    vec3 d = normalize(t * (sin_t * cos(phi)) + b * (sin_t * sin(phi)) + axis * cos_t);
#ifdef DIFFERENTIALS
    // d(cos)/du1 = -(1 - cos_half), d(sin)/du1 = -cos/sin d(cos)/du1, d(phi)/du2 = 2 pi; times 1/N.
    float step_u = 1.0 / float(side);
    float dcos = -(1.0 - cos_half) * step_u;
    float dsin = sin_t > 0.0 ? -cos_t / sin_t * dcos : 0.0;
    float dphi = 6.28318530717959 * step_u;
    Differentials x;
    x.pu = vec3(0.0);
    x.pv = vec3(0.0);
    x.du = (t * cos(phi) + b * sin(phi)) * dsin + axis * dcos;
    x.dv = (-t * sin(phi) + b * cos(phi)) * (sin_t * dphi);
#endif
    float omega = 6.28318530717959 * (1.0 - cos_half);
    vec3 power = frame.lights[l].intensity.rgb * spot_emission(l, d) * omega / float(side * side);
    int channel = 1;
    if ((constants.flags & PHOTON_TRACE_DISPERSIVE) != 0u) {
        channel = min(int(random01(id, 2u) * 3.0), 2);
        vec3 only = vec3(0.0);
        only[channel] = 3.0 * power[channel];
        power = only;
    }
    bool fresnel = (caustics.settings.w & CAUSTIC_FRESNEL) != 0u;
    vec3 o = light;
    uint interactions = 0u;
    uint refractions = 0u;
    bool straight = false;
    uint draw = 3u;
    for (uint step = 0u; step < constants.max_bounces + MAX_SKIPS + 1u; ++step) {
        RayHit h;
        if (!scene_intersect(o, d, constants.eps, 3.4e38, h)) break;
        vec3 p = o + d * h.t;
        BvhTriangle tri = bvh_triangle(h.triangle);
        uint material = objects[tri.object].material.x;
#ifdef DIFFERENTIALS
        vec3 ng_here = normalize(hit_to_world(h, cross(tri.e1, tri.e2)));
        transfer(x, d, h.t, ng_here);
#endif
        if (straight && material != MATERIAL_DIFFUSE) {
            o = p;
            continue;
        }
        if (material == MATERIAL_DIFFUSE) {
            if (interactions == 0u) break;
            store(texel, vec4(p, 1.0), vec4(d, 0.0), vec4(power, 1.0));
#ifdef DIFFERENTIALS
            imageStore(photon_footprint_u, texel, vec4(x.pu, 0.0));
            imageStore(photon_footprint_v, texel, vec4(x.pv, 0.0));
#endif
#ifdef RECEIVER_DEPOSIT
            deposit_on_receiver(p, power);
#endif
            return;
        }
        if (interactions >= constants.max_bounces) break;
        vec3 ng = normalize(hit_to_world(h, cross(tri.e1, tri.e2)));
        vec3 colour = objects[tri.object].colour.rgb;
        if (material == MATERIAL_REFLECTIVE) {
            vec3 ns = scatter_normal(h, ng);
#ifdef DIFFERENTIALS
            vec3 dnu = normal_derivative(h, tri, ng, x.pu);
            vec3 dnv = normal_derivative(h, tri, ng, x.pv);
            vec3 r0 = reflect(d, ns);
            x.du = tangent(r0, reflected_derivative(d, ns, x.du, dnu));
            x.dv = tangent(r0, reflected_derivative(d, ns, x.dv, dnv));
#endif
            d = normalize(reflect(d, ns));
            power *= colour;
            if (!fresnel) straight = true;
        } else {
            bool entering = dot(d, ng) < 0.0;
            vec3 ns = scatter_normal(h, ng);
            vec3 n = entering ? ns : -ns;
            float ior = objects[tri.object].ior[channel];
            float eta = entering ? 1.0 / ior : ior;
            float cos_i = -dot(d, n);
#ifdef DIFFERENTIALS
            vec3 dnu = normal_derivative(h, tri, ng, x.pu) * (entering ? 1.0 : -1.0);
            vec3 dnv = normal_derivative(h, tri, ng, x.pv) * (entering ? 1.0 : -1.0);
#endif
            bool reflect_now = fresnel && random01(id, draw++) < dielectric_fresnel(cos_i, eta);
            if (reflect_now) {
                if (entering && (constants.flags & PHOTON_TRACE_OUTSIDE_REFLECTION) == 0u) break;
#ifdef DIFFERENTIALS
                vec3 r0 = reflect(d, n);
                x.du = tangent(r0, reflected_derivative(d, n, x.du, dnu));
                x.dv = tangent(r0, reflected_derivative(d, n, x.dv, dnv));
#endif
                d = normalize(reflect(d, n));
            } else {
                vec3 r = refract(d, n, eta);
                if (r == vec3(0.0)) {
                    if (!fresnel) {
                        store(texel, vec4(0.0), vec4(0.0, 0.0, 0.0, PHOTON_LOST_TIR), vec4(power, 0.0));
                        return;
                    }
#ifdef DIFFERENTIALS
                    vec3 r0 = reflect(d, n);
                    x.du = tangent(r0, reflected_derivative(d, n, x.du, dnu));
                    x.dv = tangent(r0, reflected_derivative(d, n, x.dv, dnv));
#endif
                    d = normalize(reflect(d, n));
                } else {
#ifdef DIFFERENTIALS
                    x.du = tangent(r, refracted_derivative(d, n, eta, x.du, dnu));
                    x.dv = tangent(r, refracted_derivative(d, n, eta, x.dv, dnv));
#endif
                    d = normalize(r);
                }
                if (!entering && r != vec3(0.0)) power *= colour;
                if (r != vec3(0.0)) ++refractions;
                if (!fresnel && refractions >= 2u) straight = true;
            }
        }
        ++interactions;
        o = p;
    }
    // No caustic photon (direct light) or one lost on its way: it carries nothing here.
    store(texel, vec4(0.0), vec4(0.0, 0.0, 0.0, interactions == 0u ? 0.0 : PHOTON_LOST_OTHER), vec4(power, 0.0));
}
