#ifndef VPLKIT_LIGHTS_GLSL
#define VPLKIT_LIGHTS_GLSL

// Punctual lights as KHR_lights_punctual defines them, read radiometrically: a point or spot
// light's intensity (candela) as radiant intensity in W/sr, a directional light's (lux) as
// irradiance in W/m^2 on a surface facing it. `intensity` is colour x intensity.
const uint kLightDirectional = 0u;
const uint kLightPoint = 1u;
const uint kLightSpot = 2u;

struct PunctualLight {
    vec3 position;   // point and spot
    uint type;       // kLight*
    vec3 direction;  // unit; the direction the light travels (directional and spot)
    float range;     // 0: unlimited
    vec3 intensity;  // RGB: W/sr (point, spot) or W/m^2 (directional)
    float spot_scale;   // KHR_lights_punctual: 1 / max(0.001, cos(inner) - cos(outer))
    float spot_offset;  // -cos(outer) * spot_scale
};

// What a light delivers at a point: the direction towards it, the distance to it (for the
// shadow ray; 0 for a directional light, which has none), and the irradiance on a surface
// facing the light (multiply by the BRDF and <n, wi> for reflected radiance).
struct LightIncidence {
    vec3 wi;
    float distance;
    vec3 irradiance;
};

LightIncidence light_incidence(PunctualLight light, vec3 p) {
    LightIncidence r;
    if (light.type == kLightDirectional) {
        r.wi = -light.direction;
        r.distance = 0.0;
        r.irradiance = light.intensity;
        return r;
    }
    vec3 to_light = light.position - p;
    float d2 = dot(to_light, to_light);
    r.distance = sqrt(d2);
    // A shading point on the light itself has no direction to it: it gets nothing (never inf/NaN).
    if (!(r.distance > 0.0)) {
        r.wi = vec3(0.0, 0.0, 1.0);
        r.irradiance = vec3(0.0);
        return r;
    }
    r.wi = to_light / r.distance;
    float attenuation = 1.0 / d2;
    if (light.range > 0.0) {
        // KHR_lights_punctual's recommended window: reaches 0 at the range, smoothly.
        float x = r.distance / light.range;
        attenuation *= clamp(1.0 - x * x * x * x, 0.0, 1.0);
    }
    if (light.type == kLightSpot) {
        // KHR_lights_punctual's angular attenuation, squared for a smooth falloff.
        float cd = dot(light.direction, -r.wi);
        float a = clamp(cd * light.spot_scale + light.spot_offset, 0.0, 1.0);
        attenuation *= a * a;
    }
    r.irradiance = light.intensity * attenuation;
    return r;
}

#endif
