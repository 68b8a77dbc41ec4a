// game_shading: the punctual light term in the two unit conventions (Lagarde, "PI or not to PI in game
// lighting equation", 2012; docs/conventions.md). f is the BRDF value f_r(wi, wo) in 1/sr and n_dot_l = N.L
// (wi.z in the local frame); a light below the horizon (N.L <= 0) contributes nothing.

// Game units: a light of colour c lights a white Lambert surface facing it to exit radiance c, so the light's
// irradiance is E_perp = pi c and L_o = pi f c N.L (the article's "pi * BRDF * light colour * N.L").
inline rgb punctual_game(rgb f, rgb colour, real n_dot_l) {
  return f * colour * (SL_PI * max(n_dot_l, 0.0));
}

// Radiometric units: E_perp is the irradiance on a surface facing the light (W/m^2), L_o = f E_perp N.L
// (the rendering equation with a delta light). Feeding a game colour here is the "missing pi" bug.
inline rgb punctual_radiometric(rgb f, rgb e_perp, real n_dot_l) {
  return f * e_perp * max(n_dot_l, 0.0);
}

// A point light of intensity I (W/sr) at squared distance d2 > 0 from the surface: E_perp = I / d2 (the
// inverse-square law); the caller handles a surface point at the light itself.
inline rgb point_light_irradiance(rgb intensity, real distance_squared) {
  return intensity / distance_squared;
}

// The game colour that delivers an irradiance E_perp: c = E_perp / pi (docs/conventions.md).
inline rgb game_colour_from_irradiance(rgb e_perp) {
  return e_perp * SL_INV_PI;
}
