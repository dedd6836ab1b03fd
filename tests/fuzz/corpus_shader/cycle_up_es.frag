#version 300 es
precision mediump float;
#include "up.glsl"
