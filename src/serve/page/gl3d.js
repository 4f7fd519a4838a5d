// The 3D view's WebGL 2 programs (view3d.js): the stems, each one
// instance of a four-corner strip a band of its width in its colour,
// faded toward the background with depth; the leaves, triangles lit by
// their facing on both sides; the volumes, translucent and lit by their
// facing. All project as render/view.rs does: orthographic, `rot` the
// camera's rows, `scale` pixels a canvas unit.

export const STEM_VS = `#version 300 es
in vec2 corner;
in vec3 a;
in vec3 b;
in vec2 wd;
in vec3 col;
uniform mat3 rot;
uniform vec3 centre;
uniform float scale;
uniform vec2 viewport;
uniform float pixelWidths;
uniform float upTo;
uniform float range;
out float fade;
out vec3 colour;
void main() {
  colour = col;
  if (wd.y > upTo) { gl_Position = vec4(2.0, 2.0, 2.0, 1.0); return; }
  vec3 pa = rot * (a - centre);
  vec3 pb = rot * (b - centre);
  vec2 sa = pa.xy * scale;
  vec2 sb = pb.xy * scale;
  vec2 d = sb - sa;
  float len = length(d);
  vec2 dir = len > 1e-6 ? d / len : vec2(1.0, 0.0);
  vec2 nrm = vec2(-dir.y, dir.x);
  float w = max(pixelWidths > 0.0 ? wd.x * pixelWidths : wd.x * scale, 1.0) * 0.5;
  vec2 p = mix(sa, sb, corner.x) + nrm * corner.y * w + dir * (corner.x * 2.0 - 1.0) * w;
  float z = mix(pa.z, pb.z, corner.x) / range;
  fade = clamp(z * 0.5 + 0.5, 0.0, 1.0);
  gl_Position = vec4(p.x * 2.0 / viewport.x, -p.y * 2.0 / viewport.y, z, 1.0);
}`;

export const STEM_FS = `#version 300 es
precision mediump float;
in float fade;
in vec3 colour;
uniform vec3 background;
out vec4 outColour;
void main() {
  outColour = vec4(mix(colour, background, 0.35 * fade), 1.0);
}`;

export const LEAF_VS = `#version 300 es
in vec3 position;
in vec3 normal;
in vec3 col;
uniform mat3 rot;
uniform vec3 centre;
uniform float scale;
uniform vec2 viewport;
uniform float range;
out vec3 colour;
void main() {
  vec3 p = rot * (position - centre);
  vec3 n = rot * normal;
  colour = col * (0.55 + 0.45 * abs(normalize(n).z));
  gl_Position = vec4(p.x * scale * 2.0 / viewport.x, -p.y * scale * 2.0 / viewport.y, p.z / range, 1.0);
}`;

export const LEAF_FS = `#version 300 es
precision mediump float;
in vec3 colour;
out vec4 outColour;
void main() {
  outColour = vec4(colour, 1.0);
}`;

export const VOLUME_VS = `#version 300 es
in vec3 position;
in vec3 normal;
uniform mat3 rot;
uniform vec3 centre;
uniform float scale;
uniform vec2 viewport;
out float light;
void main() {
  vec3 p = rot * (position - centre);
  vec3 n = rot * normal;
  light = 0.45 + 0.55 * abs(normalize(n).z);
  gl_Position = vec4(p.x * scale * 2.0 / viewport.x, -p.y * scale * 2.0 / viewport.y, 0.0, 1.0);
}`;

export const VOLUME_FS = `#version 300 es
precision mediump float;
in float light;
uniform vec4 colour;
out vec4 outColour;
void main() {
  outColour = vec4(colour.rgb * light, colour.a);
}`;

export function compile(gl, vs, fs) {
  const prog = gl.createProgram();
  for (const [type, text] of [[gl.VERTEX_SHADER, vs], [gl.FRAGMENT_SHADER, fs]]) {
    const s = gl.createShader(type);
    gl.shaderSource(s, text);
    gl.compileShader(s);
    if (!gl.getShaderParameter(s, gl.COMPILE_STATUS)) throw new Error(gl.getShaderInfoLog(s));
    gl.attachShader(prog, s);
  }
  gl.linkProgram(prog);
  if (!gl.getProgramParameter(prog, gl.LINK_STATUS)) throw new Error(gl.getProgramInfoLog(prog));
  const u = {};
  const n = gl.getProgramParameter(prog, gl.ACTIVE_UNIFORMS);
  for (let i = 0; i < n; i++) {
    const name = gl.getActiveUniform(prog, i).name;
    u[name] = gl.getUniformLocation(prog, name);
  }
  return { prog, u, attr: (name) => gl.getAttribLocation(prog, name) };
}
