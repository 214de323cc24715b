// Unpolarised Fresnel reflectance of a dielectric interface, for cos_i on the incident side and
// eta = n_i / n_t; 1 under total internal reflection. Shared by the eye's image-space
// refraction and the photons' transmittance.
#ifndef FRESNEL_GLSL
#define FRESNEL_GLSL

float dielectric_fresnel(float cos_i, float eta) {
    float sin_t2 = eta * eta * max(0.0, 1.0 - cos_i * cos_i);
    if (sin_t2 >= 1.0) return 1.0;
    float cos_t = sqrt(1.0 - sin_t2);
    float rs = (eta * cos_i - cos_t) / (eta * cos_i + cos_t);
    float rp = (cos_i - eta * cos_t) / (cos_i + eta * cos_t);
    return 0.5 * (rs * rs + rp * rp);
}

#endif
