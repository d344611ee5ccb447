// glTF 2.0's metallic-roughness BRDF (its Appendix B: GGX distribution, height-correlated Smith
// visibility, Schlick's Fresnel, Lambert diffuse) lit by the environment (split-sum image-based
// lighting, Karis 2013, with Fdez-Aguera's 2019 multiple-scattering energy compensation) and by
// punctual lights. Roughness is glTF's perceptual roughness; alpha = roughness^2.
#ifndef PBR_GLSL
#define PBR_GLSL

#define PBR_PI 3.14159265358979

struct SurfacePoint {
  highp vec3 diffuse_color;  // base colour * (1 - metallic)
  highp vec3 f0;             // reflectance at normal incidence: 0.04 for dielectrics, the base colour for metals
  highp float roughness;     // perceptual
  highp vec3 n;              // unit normal
  highp vec3 v;              // unit direction to the eye
  highp float nv;            // dot(n, v), kept off 0
};

SurfacePoint surface_point(highp vec3 base_color, highp float metallic, highp float roughness, highp vec3 n, highp vec3 v) {
  SurfacePoint s;
  s.diffuse_color = base_color * (1.0 - metallic);
  s.f0 = mix(vec3(0.04), base_color, metallic);
  // Below about 0.03 the GGX lobe is narrower than a texel of the prefiltered map and the punctual
  // highlight aliases; clamped there as most real-time renderers do.
  s.roughness = clamp(roughness, 0.03, 1.0);
  s.n = n;
  s.v = v;
  s.nv = clamp(dot(n, v), 1e-4, 1.0);
  return s;
}

// Split-sum environment light, split into what ambient occlusion scales (diffuse) and what specular
// occlusion scales. `lut` is (A, B) of the split-sum table at (nv, roughness); `irradiance` the
// cosine-convolved environment / pi along n; `prefiltered` the environment prefiltered for the
// roughness along the reflection. With F0 = 1 (white metal) or a white dielectric, a uniform
// environment of radiance L returns exactly L: the white furnace holds at every roughness.
void environment_light(SurfacePoint s, highp vec2 lut, highp vec3 irradiance, highp vec3 prefiltered, out highp vec3 diffuse,
                       out highp vec3 specular) {
  highp vec3 fss_ess = s.f0 * lut.x + lut.y;
  highp float ems = 1.0 - (lut.x + lut.y);
  highp vec3 f_avg = s.f0 + (1.0 - s.f0) / 21.0;
  highp vec3 fms_ems = ems * fss_ess * f_avg / (1.0 - f_avg * ems);
  highp vec3 kd = s.diffuse_color * (1.0 - fss_ess - fms_ems);
  diffuse = (fms_ems + kd) * irradiance;
  specular = fss_ess * prefiltered;
}

// Lagarde and de Rousiers 2014 (Moving Frostbite to PBR, 4.10.2): how much of the specular lobe
// an ambient visibility `ao` leaves, from the view angle and the lobe's width. Near a grazing
// view or for a tight lobe, less than ao; for a broad lobe seen head on, ao itself.
highp float specular_occlusion(highp float nv, highp float ao, highp float roughness) {
  highp float alpha = roughness * roughness;
  return clamp(pow(nv + ao, exp2(-16.0 * alpha - 1.0)) - 1.0 + ao, 0.0, 1.0);
}

// Outgoing radiance from a punctual light arriving along unit `l` with irradiance `e` (normal to
// the light), glTF Appendix B.
highp vec3 punctual_light(SurfacePoint s, highp vec3 l, highp vec3 e) {
  highp float nl = dot(s.n, l);
  if (nl <= 0.0) return vec3(0.0);
  highp vec3 h = normalize(l + s.v);
  highp float nh = max(dot(s.n, h), 0.0), vh = max(dot(s.v, h), 0.0);
  highp float alpha = s.roughness * s.roughness, a2 = alpha * alpha;
  highp float d_denominator = nh * nh * (a2 - 1.0) + 1.0;
  highp float distribution = a2 / (PBR_PI * d_denominator * d_denominator);
  highp float visibility = 0.5 / (nl * sqrt(s.nv * s.nv * (1.0 - a2) + a2) + s.nv * sqrt(nl * nl * (1.0 - a2) + a2));
  highp float grazing = 1.0 - vh, grazing_squared = grazing * grazing;  // pow(x, 5) is two transcendentals on llvmpipe
  highp vec3 fresnel = s.f0 + (1.0 - s.f0) * (grazing_squared * grazing_squared * grazing);
  return ((1.0 - fresnel) * s.diffuse_color / PBR_PI + fresnel * distribution * visibility) * e * nl;
}

// The environment's diffuse light (irradiance / pi) from its 9 spherical-harmonic coefficients, in
// the order and basis of scene::Environment::irradiance_sh; clamped at 0 as the CPU evaluation is
// (band 2 rings below zero around a small bright light).
highp vec3 sh_irradiance(highp vec4 c[9], highp vec3 n) {
  return max(vec3(0.0), c[0].rgb * 0.282095 + c[1].rgb * (0.488603 * n.y) + c[2].rgb * (0.488603 * n.z) + c[3].rgb * (0.488603 * n.x) +
         c[4].rgb * (1.092548 * n.x * n.y) + c[5].rgb * (1.092548 * n.y * n.z) +
         c[6].rgb * (0.315392 * (3.0 * n.z * n.z - 1.0)) + c[7].rgb * (1.092548 * n.x * n.z) +
         c[8].rgb * (0.546274 * (n.x * n.x - n.y * n.y)));
}

#endif
