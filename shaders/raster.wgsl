// Rasterised direct lighting: Lambert diffuse plus a normalised Phong glossy lobe, per
// light, no shadows. Radiance leaving a surface toward the eye:
//   L = emissive + Σ_lights E_l · [ k_d/π · (n·l) + k_s · (r+1)/(2π) · max(ρ·l, 0)^r ]
// where E_l is the light's irradiance on a plane facing it and ρ the mirrored view vector.

@group(0) @binding(0) var<uniform> frame: Frame;
@group(0) @binding(1) var<storage, read> lights: array<Light>;

@group(1) @binding(0) var<uniform> material: Material;
@group(1) @binding(1) var base_color_texture: texture_2d<f32>;
@group(1) @binding(2) var base_color_sampler: sampler;

struct VertexIn {
    @location(0) position: vec3<f32>,
    @location(1) normal: vec3<f32>,
    @location(2) uv: vec2<f32>,
};

struct VertexOut {
    @builtin(position) clip: vec4<f32>,
    @location(0) world_position: vec3<f32>,
    @location(1) normal: vec3<f32>,
    @location(2) uv: vec2<f32>,
};

@vertex
fn vs_main(v: VertexIn) -> VertexOut {
    var out: VertexOut;
    out.clip = frame.view_proj * vec4<f32>(v.position, 1.0);
    out.world_position = v.position;
    out.normal = v.normal;
    out.uv = v.uv;
    return out;
}

// Irradiance (per unit area facing the light) and the unit direction toward the light.
struct Incidence {
    irradiance: vec3<f32>,
    to_light: vec3<f32>,
};

fn incidence(light: Light, p: vec3<f32>) -> Incidence {
    var result: Incidence;
    if light.kind == LIGHT_DIRECTIONAL {
        result.to_light = -light.direction_range.xyz;
        result.irradiance = light.intensity_rgb.rgb;
        return result;
    }
    let offset = light.position.xyz - p;
    let distance2 = max(dot(offset, offset), 1e-8);
    result.to_light = offset * inverseSqrt(distance2);
    var falloff = 1.0 / distance2;
    let range = light.direction_range.w;
    if range > 0.0 {
        // KHR_lights_punctual's recommended smooth window to zero at `range`.
        let ratio2 = distance2 / (range * range);
        let window = clamp(1.0 - ratio2 * ratio2, 0.0, 1.0);
        falloff *= window * window;
    }
    if light.kind == LIGHT_AREA {
        falloff *= max(dot(-result.to_light, light.direction_range.xyz), 0.0);
    }
    if light.kind == LIGHT_SPOT {
        let cos_angle = dot(-result.to_light, light.direction_range.xyz);
        let t = clamp((cos_angle - light.spot_cone.x) * light.spot_cone.y, 0.0, 1.0);
        falloff *= t * t;
    }
    result.irradiance = light.intensity_rgb.rgb * falloff;
    return result;
}

@fragment
fn fs_main(in: VertexOut, @builtin(front_facing) front_facing: bool) -> @location(0) vec4<f32> {
    var base = material.base_color;
    if material.params.w > 0.5 {
        base *= textureSample(base_color_texture, base_color_sampler, in.uv);
    }
    let metallic = material.params.x;
    let dielectric_specular = 0.04 * material.params.y;
    let k_d = base.rgb * (1.0 - metallic) * (1.0 - dielectric_specular);
    let k_s = mix(vec3<f32>(dielectric_specular), base.rgb, metallic);
    let exponent = material.params.z;

    var n = normalize(in.normal);
    if !front_facing {
        n = -n;
    }
    let to_eye = normalize(frame.camera_position.xyz - in.world_position);
    let mirrored = reflect(-to_eye, n);
    let lobe_norm = (exponent + 1.0) / (2.0 * PI);

    // Environment: diffuse only, from its irradiance SH (clamped at 0 against ringing).
    var radiance = material.emissive.rgb + k_d / PI * max(sh3_eval(frame.environment_irradiance, n), vec3<f32>(0.0));
    for (var i = 0u; i < frame.light_count; i++) {
        let light = lights[i];
        let inc = incidence(light, in.world_position);
        let n_dot_l = dot(n, inc.to_light);
        if n_dot_l <= 0.0 {
            continue;
        }
        let cos_mirror = max(dot(mirrored, inc.to_light), 1e-8);
        // exp2(r·log2 c) rather than pow: equals 1 at r = 0 even where c underflows.
        let glossy = lobe_norm * exp2(exponent * log2(cos_mirror));
        radiance += inc.irradiance * (k_d / PI * n_dot_l + k_s * glossy);
    }
    return vec4<f32>(tonemap_aces_fit(frame.exposure * radiance), 1.0);
}
