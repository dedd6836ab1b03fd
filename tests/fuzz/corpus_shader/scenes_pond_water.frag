#version 330 compatibility
// Sky reflection over the floor seen through the water, weighted by a
// (1 - E.N)^q Fresnel term; alpha lets the floor show through.
uniform vec4 uWaterColor;
uniform vec3 uSkyColor;
uniform float uFresnelPower;
uniform float uClarity;
in vec3 vNormalEye;
in vec3 vPosEye;
out vec4 fragColor;

void main() {
    vec3 n = normalize(vNormalEye);
    vec3 e = normalize(-vPosEye);
    float fresnel = pow(1.0 - clamp(dot(e, n), 0.0, 1.0), uFresnelPower);
    vec3 color = mix(uWaterColor.rgb, uSkyColor, fresnel);
#ifdef SPECULAR
    vec3 l = normalize((gl_ModelViewMatrix * vec4(0.3, 1.0, -0.6, 0.0)).xyz);
    color += vec3(pow(max(dot(reflect(-l, n), e), 0.0), 120.0));
#endif
    float alpha = mix(1.0 - uClarity, 1.0, fresnel);
    fragColor = vec4(color, clamp(alpha, 0.0, 1.0));
}
