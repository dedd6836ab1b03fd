// scene_waves.glsl: figures of the scene's whole wave set that packs/
// caustic_tex's water takes, from the raw wave uniforms (waves.glsl, included
// first). They depend on the uniforms alone: water.vert works them out and
// hands them to water.frag as flat outputs. No #version here.
#ifndef SCENE_WAVES_GLSL
#define SCENE_WAVES_GLSL

// The amplitudes of every wave, noise included (foam strength).
float waveAmpSum() {
    float s = abs(uNoiseAmp);
    for (int i = 0; i < ROLLED(WAVES_MAX); i++) {
        if (i < uSineCount && uSineLength[i] > 0.0) s += abs(uSineAmp[i]);
        if (i < uGerstnerCount && uGerstnerLength[i] > 0.0) s += abs(uGerstnerAmp[i]);
    }
    return s;
}

// The scene's waves as the caustics see them: the curvature-weighted
// (k^2 A: what focuses light) mean wavelength, 0 without waves; and each
// kind's most curved wave's phase velocity (the pattern travels with it).
float sceneCausticWavelength(out vec2 velS, out vec2 velG) {
    float W = 0.0, LW = 0.0, bestS = 0.0, bestG = 0.0;
    velS = velG = vec2(0.0);
    for (int i = 0; i < ROLLED(WAVES_MAX); i++) {
        for (int kind = 0; kind < ROLLED(2); kind++) {
            bool g = kind == 1;
            if (i >= (g ? uGerstnerCount : uSineCount)) continue;
            float L = g ? uGerstnerLength[i] : uSineLength[i];
            float A = abs(g ? uGerstnerAmp[i] : uSineAmp[i]);
            if (L <= 0.0 || A == 0.0) continue;
            float k = WAVES_TWO_PI / L, w = k * k * A;
            W += w;
            LW += L * w;
            float ang = radians(g ? uGerstnerAngle[i] : uSineAngle[i]);
            vec2 v = wavesPhaseSpeed(g ? uGerstnerSpeed[i] : uSineSpeed[i], L) * vec2(cos(ang), sin(ang));
            if (g && w > bestG) { bestG = w; velG = v; }
            if (!g && w > bestS) { bestS = w; velS = v; }
        }
    }
    return W > 0.0 ? LW / W : 0.0;
}

#endif // SCENE_WAVES_GLSL
