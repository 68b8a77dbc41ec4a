// cube: cube-map addressing and the seamless bilinear read, written once for the C++ (envmap/cubemap.h,
// envmap/prefilter_ggx.h), the exported shaders and the browser explorer.
// - Faces in the OpenGL order +X, -X, +Y, -Y, +Z, -Z, each addressed as OpenGL 4.6 table 8.19 does: for a
//   direction r with major axis ma, s = (sc/|ma| + 1)/2, t = (tc/|ma| + 1)/2 (ties to X, then Y); texel (x, y)
//   of an N x N face covers s in [x/N, (x+1)/N], t in [y/N, (y+1)/N].
// - The seamless read: bilinear between the four texel centres around the direction, where a centre beyond the
//   face's edge is the texel of the neighbouring face that holds that centre's direction (and a centre beyond
//   a corner, where three faces meet, the mean of the three texels there), so the read is continuous across
//   edges as GL_TEXTURE_CUBE_MAP_SEAMLESS is (OpenGL 4.6 section 8.13.1; the corner rule is ours).
// The texels come from the language-specific fetches cube_texel(cube, face, x, y) and cube_size(cube) (C++:
// kernels.h over the cubes bound to the calling thread; shaders: texelFetch on a 2D array texture, one layer a
// face, one mip level a cube).

const int CUBE_FACE_POS_X = 0;
const int CUBE_FACE_NEG_X = 1;
const int CUBE_FACE_POS_Y = 2;
const int CUBE_FACE_NEG_Y = 3;
const int CUBE_FACE_POS_Z = 4;
const int CUBE_FACE_NEG_Z = 5;

struct CubeFaceCoord {
  int face;
  real s;  // [0, 1] across the face
  real t;  // [0, 1] down the face
};

// Direction (not necessarily unit, not zero) -> face and face coordinates (OpenGL table 8.19).
inline CubeFaceCoord cube_face_coord(vec3 r) {
  real ax = abs(r.x);
  real ay = abs(r.y);
  real az = abs(r.z);
  CubeFaceCoord c;
  real sc = 0.0;
  real tc = 0.0;
  real ma = 0.0;
  if (ax >= ay && ax >= az) {
    ma = ax;
    if (r.x >= 0.0) {
      c.face = CUBE_FACE_POS_X;
      sc = -r.z;
      tc = -r.y;
    } else {
      c.face = CUBE_FACE_NEG_X;
      sc = r.z;
      tc = -r.y;
    }
  } else if (ay >= az) {
    ma = ay;
    if (r.y >= 0.0) {
      c.face = CUBE_FACE_POS_Y;
      sc = r.x;
      tc = r.z;
    } else {
      c.face = CUBE_FACE_NEG_Y;
      sc = r.x;
      tc = -r.z;
    }
  } else {
    ma = az;
    if (r.z >= 0.0) {
      c.face = CUBE_FACE_POS_Z;
      sc = r.x;
      tc = -r.y;
    } else {
      c.face = CUBE_FACE_NEG_Z;
      sc = -r.x;
      tc = -r.y;
    }
  }
  // ma > 0 for any non-zero r (the largest of |x|, |y|, |z|).
  c.s = 0.5 * (sc / ma + 1.0);
  c.t = 0.5 * (tc / ma + 1.0);
  return c;
}

// Face and face coordinates -> unit direction: the inverse of table 8.19.
inline vec3 cube_face_direction(int face, real s, real t) {
  real sc = 2.0 * s - 1.0;
  real tc = 2.0 * t - 1.0;
  vec3 r = vec3(-sc, -tc, -1.0);
  if (face == CUBE_FACE_POS_X) {
    r = vec3(1.0, -tc, -sc);
  } else if (face == CUBE_FACE_NEG_X) {
    r = vec3(-1.0, -tc, sc);
  } else if (face == CUBE_FACE_POS_Y) {
    r = vec3(sc, 1.0, tc);
  } else if (face == CUBE_FACE_NEG_Y) {
    r = vec3(sc, -1.0, -tc);
  } else if (face == CUBE_FACE_POS_Z) {
    r = vec3(sc, -tc, 1.0);
  }
  return normalize(r);
}

// The texel of a neighbouring face that holds the direction of the centre of texel (x, y) of `face`, a centre
// one texel beyond the face's edge (x or y in {-1, n}).
inline rgb cube_texel_beyond_edge(int cube, int n, int face, int x, int y) {
  real fn = real(n);
  CubeFaceCoord q = cube_face_coord(cube_face_direction(face, (real(x) + 0.5) / fn, (real(y) + 0.5) / fn));
  int qx = clamp(int(q.s * fn), 0, n - 1);
  int qy = clamp(int(q.t * fn), 0, n - 1);
  return cube_texel(cube, q.face, qx, qy);
}

// Texel (x, y) of `face` for x, y in [-1, n]: inside the face its own texel; beyond one edge the neighbouring
// face's (cube_texel_beyond_edge); beyond a corner the mean of the corner texel and the two beyond its edges.
inline rgb cube_texel_across_edges(int cube, int n, int face, int x, int y) {
  bool x_in = x >= 0 && x < n;
  bool y_in = y >= 0 && y < n;
  if (x_in && y_in) return cube_texel(cube, face, x, y);
  if (x_in || y_in) return cube_texel_beyond_edge(cube, n, face, x, y);
  int cx = clamp(x, 0, n - 1);
  int cy = clamp(y, 0, n - 1);
  return (cube_texel(cube, face, cx, cy) + cube_texel_beyond_edge(cube, n, face, x, cy) +
          cube_texel_beyond_edge(cube, n, face, cx, y)) / 3.0;
}

// The seamless bilinear read of cube `cube` along dir (not zero): bilinear between the four texel centres
// around dir's face coordinates, centres beyond the face's edges taken across them.
inline rgb cube_sample_seamless(int cube, vec3 dir) {
  int n = cube_size(cube);
  CubeFaceCoord c = cube_face_coord(dir);
  real fx = c.s * real(n) - 0.5;  // texel centres at integer fx
  real fy = c.t * real(n) - 0.5;
  int x0 = clamp(int(floor(fx)), -1, n - 1);
  int y0 = clamp(int(floor(fy)), -1, n - 1);
  real ax = clamp(fx - real(x0), 0.0, 1.0);
  real ay = clamp(fy - real(y0), 0.0, 1.0);
  rgb lo = cube_texel_across_edges(cube, n, c.face, x0, y0) * (1.0 - ax) +
           cube_texel_across_edges(cube, n, c.face, x0 + 1, y0) * ax;
  rgb hi = cube_texel_across_edges(cube, n, c.face, x0, y0 + 1) * (1.0 - ax) +
           cube_texel_across_edges(cube, n, c.face, x0 + 1, y0 + 1) * ax;
  return lo * (1.0 - ay) + hi * ay;
}
