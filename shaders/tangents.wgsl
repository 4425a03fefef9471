// Deformed tangents: for each listed vertex, its rest tangent's xyz turned by the minimal
// rotation taking its rest normal n0 to its deformed normal n (Rodrigues, about k = n0 x n:
// R v = c v + k x v + k (k . v) / (1 + c), c = n0 . n), made orthogonal to n (Gram-Schmidt) and
// normalized; w (the glTF handedness, +-1) copied. Degenerate cases: n0 ~ -n (1 + c <= OPPOSITE)
// takes the half turn about any_perpendicular(n0); a zero n0 or n turns nothing; a result
// parallel to n (or zero) becomes any_perpendicular(n), zero when n is zero. No NaN comes out
// of finite input. f64 reference: src/normals/tangents.rs.
// Composed after layout.wgsl. Twin: src/cpu/tangents.rs.

@group(0) @binding(0) var<uniform> params: DispatchParams;
// This chunk's vertices (global indices, ascending). The per-vertex windows below start at
// vertex params.first_vertex.
@group(0) @binding(1) var<storage, read> vertices: array<u32>;
// Unit or zero normals, tightly packed xyz: at rest, and of the deformed mesh.
@group(0) @binding(2) var<storage, read> rest_normals: array<f32>;
@group(0) @binding(3) var<storage, read> normals: array<f32>;
// Tangents xyzw, 16 bytes a vertex: the host's at rest, and the output.
@group(0) @binding(4) var<storage, read> rest_tangents: array<vec4<f32>>;
@group(0) @binding(5) var<storage, read_write> tangents: array<vec4<f32>>;

const OPPOSITE: f32 = 1e-4;
const PARALLEL: f32 = 1e-12;

// A unit vector perpendicular to n: n x e, normalized, for the axis e least aligned with n
// (the first of x, y, z on ties); zero for a zero n.
fn any_perpendicular(n: vec3<f32>) -> vec3<f32> {
    let a = abs(n);
    var e = vec3<f32>(0.0, 0.0, 1.0);
    if (a.x <= a.y && a.x <= a.z) {
        e = vec3<f32>(1.0, 0.0, 0.0);
    } else if (a.y <= a.z) {
        e = vec3<f32>(0.0, 1.0, 0.0);
    }
    let p = cross(n, e);
    let length2 = dot(p, p);
    if (length2 > 0.0) {
        return p * inverseSqrt(length2);
    }
    return vec3<f32>(0.0);
}

fn deformed_tangent(n0: vec3<f32>, n: vec3<f32>, t: vec4<f32>) -> vec4<f32> {
    var v = t.xyz;
    if (any(n0 != vec3<f32>(0.0)) && any(n != vec3<f32>(0.0))) {
        let c = dot(n0, n);
        if (1.0 + c > OPPOSITE) {
            let k = cross(n0, n);
            v = c * v + cross(k, v) + k * (dot(k, v) / (1.0 + c));
        } else {
            // The half turn about a unit axis a perpendicular to n0.
            let a = any_perpendicular(n0);
            v = 2.0 * a * dot(a, v) - v;
        }
    }
    let u = v - n * dot(n, v);
    let length2 = dot(u, u);
    var d = any_perpendicular(n);
    if (length2 > PARALLEL * dot(v, v)) {
        d = u * inverseSqrt(length2);
    }
    return vec4<f32>(d, t.w);
}

@compute @workgroup_size(WORKGROUP_SIZE)
fn tangents_main(
    @builtin(workgroup_id) group: vec3<u32>,
    @builtin(num_workgroups) groups: vec3<u32>,
    @builtin(local_invocation_index) lane: u32,
) {
    let l = invocation_index(group, groups, lane);
    if (l >= params.vertex_count) {
        return;
    }
    let o = vertices[l] - params.first_vertex;
    let n0 = vec3<f32>(rest_normals[3u * o], rest_normals[3u * o + 1u], rest_normals[3u * o + 2u]);
    let n = vec3<f32>(normals[3u * o], normals[3u * o + 1u], normals[3u * o + 2u]);
    tangents[o] = deformed_tangent(n0, n, rest_tangents[o]);
}
