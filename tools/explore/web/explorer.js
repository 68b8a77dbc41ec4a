// shadelab explorer (docs/explorer.md). Every number on this page comes from the library compiled to
// WebAssembly (shadelab_wasm.js, tools/explore/wasm/explore_api.cpp) or from its exported GLSL ES run in
// WebGL 2; this file only parses the URL, lays out controls and draws. It evaluates no formula itself.
'use strict';

(function () {
  const $ = (id) => document.getElementById(id);
  let lib = null;
  let models = [];
  // The HDRIs `shadelab explore` baked with the game renderer's bake (environments.js, env-NAME.js; site.h).
  const ENVIRONMENTS = window.shadelabEnvironments ||
    { names: [], default: null, size: 0, specular_size: 0, message: 'no HDRI: environments.js did not load', problems: [] };

  // Query keys that are not model parameters, with their defaults (strings, as in the URL).
  // The sphere's view transform (URL parameter `tone`): `shadelab render --view` names (clamp is standard, its older
  // name) and kernels/display.sl's VIEW_* numbers, which the shader's view_transform takes.
  const TONE_VIEWS = { clamp: 0, standard: 0, filmic: 1, 'pbr-neutral': 2, agx: 3, aces: 4 };
  const VIEW_DEFAULTS = {
    theta: '0,15,30,45,60,75,85,89',
    wi: '0,0,1',
    wo: '0.5,0,0.8660254037844387',
    theta_in: '45',
    fixed: 'light',
    scale: 'linear',
    cos: '0',
    units: 'game',
    light_pos: '2,2,3',
    light: '1',
    exposure: '0',
    tone: 'clamp',
    lighting: 'point',
    env: ENVIRONMENTS.default || 'forest',
    overlay: '',
  };
  // Overlaid models, drawn over the lobe and albedo views in these colours (the first model keeps its own).
  const OVERLAY_COLOURS = ['#6a1b9a', '#00838f', '#ef6c00', '#5d4037', '#ad1457', '#558b2f'];
  const DEFAULT_MODEL = 'blinn-phong-modified';
  // The sphere's view: the C++ game renderer's pinhole camera (render/game_renderer.cpp) with these values;
  // the tests render the same scene with `shadelab render --mode game` (docs/explorer.md).
  const SPHERE = { center: [0, 0, 0], radius: 1, camera: { position: [0, 0, 4], look_at: [0, 0, 0], up: [0, 1, 0], fov: 35 },
                   spp: 4 };
  const ALBEDO_CURVE = [0, 5, 10, 15, 20, 25, 30, 35, 40, 45, 50, 55, 60, 65, 70, 75, 80, 85, 89];

  let state = null;
  let errors = [];

  function call(request) {
    const text = lib.ccall('shadelab_call', 'string', ['string'], [JSON.stringify(request)]);
    return JSON.parse(text);
  }

  function modelInfo(name) { return models.find((m) => m.name === name); }

  // A parameter's value: set explicitly, or the registry's default.
  function effective(name) {
    if (name in state.params) return state.params[name];
    return modelInfo(state.model).params.find((p) => p.name === name).default;
  }

  // Sets a parameter; where the library refuses the combination (alternatives such as m and n), the other
  // explicitly set parameters that conflict are dropped, so the last one set wins. Returns the error, if any.
  function setParam(name, value) {
    const ok = (params) => !call({ op: 'eval', model: state.model, params, wi: [0, 0, 1], wo: [0, 0, 1] }).error;
    const alone = call({ op: 'eval', model: state.model, params: { [name]: value }, wi: [0, 0, 1], wo: [0, 0, 1] });
    if (alone.error) return alone.error;
    const next = Object.assign({}, state.params, { [name]: value });
    for (const other of Object.keys(next)) {
      if (ok(next)) break;
      if (other !== name) delete next[other];
    }
    state.params = next;
    return null;
  }

  function showErrors() {
    const box = $('shadelab-error');
    box.hidden = errors.length === 0;
    box.textContent = errors.join('\n');
  }

  function numbers(text, count, key) {
    const parts = String(text).split(',').map((s) => s.trim());
    const values = parts.map(Number);
    if (parts.some((s) => s === '') || values.some((v) => !Number.isFinite(v)) || (count && values.length !== count)) {
      throw new Error(`URL parameter '${key}': '${text}' is not ${count ? count + ' numbers x,y,z' : 'a list of numbers'}`);
    }
    return values;
  }

  // The state from a query string; bad entries are reported (naming the parameter) and replaced by defaults.
  function stateFromQuery(search) {
    const q = new URLSearchParams(search);
    const problems = [];
    let model = q.get('model') || DEFAULT_MODEL;
    if (!modelInfo(model)) {
      problems.push(`URL parameter 'model': unknown model '${model}' (models: ${models.map((m) => m.name).join(', ')})`);
      model = DEFAULT_MODEL;
    }
    const info = modelInfo(model);
    const params = {};  // the parameters set explicitly; the others keep the registry's defaults
    for (const [key, value] of q.entries()) {
      if (key === 'model' || key in VIEW_DEFAULTS) continue;
      if (!info.params.some((p) => p.name === key)) {
        problems.push(`URL parameter '${key}': not a parameter of ${model} (its parameters: ${info.params.map((p) => p.name).join(', ')})`);
        continue;
      }
      // Each parameter alone through the library's own validation, so that the message names it.
      // Each parameter through the library's own validation, alone and with those before it (the library
      // refuses alternatives given together, such as cook-torrance's m and n), so the message names it.
      let probe = call({ op: 'eval', model, params: { [key]: value }, wi: [0, 0, 1], wo: [0, 0, 1] });
      if (!probe.error) probe = call({ op: 'eval', model, params: Object.assign({}, params, { [key]: value }), wi: [0, 0, 1], wo: [0, 0, 1] });
      if (probe.error) problems.push(`URL parameter '${key}': ${probe.error}`);
      else params[key] = value;
    }
    const view = {};
    for (const key of Object.keys(VIEW_DEFAULTS)) view[key] = q.has(key) ? q.get(key) : VIEW_DEFAULTS[key];
    const checks = {
      theta: () => { numbers(view.theta, 0, 'theta').forEach((t) => { if (!(t >= 0 && t < 90)) throw new Error(`URL parameter 'theta': ${t} is out of range [0, 90) degrees`); }); },
      wi: () => numbers(view.wi, 3, 'wi'),
      wo: () => numbers(view.wo, 3, 'wo'),
      light_pos: () => numbers(view.light_pos, 3, 'light_pos'),
      light: () => { const v = numbers(view.light, 0, 'light'); if (!(v.length === 1 || v.length === 3) || v.some((x) => x < 0)) throw new Error(`URL parameter 'light': '${view.light}' is not a value or r,g,b >= 0`); },
      theta_in: () => { const t = Number(view.theta_in); if (!(t >= 0 && t < 90)) throw new Error(`URL parameter 'theta_in': '${view.theta_in}' is out of range [0, 90) degrees`); },
      exposure: () => { const e = Number(view.exposure); if (!Number.isFinite(e) || Math.abs(e) > 64) throw new Error(`URL parameter 'exposure': '${view.exposure}' is not a number in [-64, 64] stops`); },
      fixed: () => { if (!['light', 'viewer'].includes(view.fixed)) throw new Error(`URL parameter 'fixed': '${view.fixed}' is not light or viewer`); },
      scale: () => { if (!['linear', 'log'].includes(view.scale)) throw new Error(`URL parameter 'scale': '${view.scale}' is not linear or log`); },
      cos: () => { if (!['0', '1'].includes(view.cos)) throw new Error(`URL parameter 'cos': '${view.cos}' is not 0 or 1`); },
      units: () => { if (!['game', 'radiometric'].includes(view.units)) throw new Error(`URL parameter 'units': '${view.units}' is not game or radiometric`); },
      tone: () => { if (!(view.tone in TONE_VIEWS)) throw new Error(`URL parameter 'tone': '${view.tone}' is not one of ${Object.keys(TONE_VIEWS).join(', ')}`); },
      lighting: () => {
        if (!['point', 'hdri', 'both'].includes(view.lighting)) throw new Error(`URL parameter 'lighting': '${view.lighting}' is not point, hdri or both`);
        if (view.lighting !== 'point' && ENVIRONMENTS.names.length === 0) throw new Error(`URL parameter 'lighting': ${ENVIRONMENTS.message}`);
      },
      overlay: () => parseOverlay(view.overlay),
      env: () => {
        if (ENVIRONMENTS.names.length > 0 && !ENVIRONMENTS.names.includes(view.env)) {
          throw new Error(`URL parameter 'env': unknown HDRI '${view.env}' (HDRIs: ${ENVIRONMENTS.names.join(', ')})`);
        }
      },
    };
    for (const [key, check] of Object.entries(checks)) {
      try { check(); } catch (e) { problems.push(e.message); view[key] = VIEW_DEFAULTS[key]; }
    }
    return { state: { model, params, view }, problems };
  }

  // `overlay`: models drawn over the first, SPEC;SPEC with SPEC = model[:name=value]... (values as in the URL,
  // e.g. lambert:kd=0.5;cook-torrance:m=0.2:f0=1,0.78,0.34). Each through the library's own validation;
  // throws naming the URL parameter.
  function parseOverlay(text) {
    if (text === '') return [];
    const specs = String(text).split(';');
    if (specs.length > OVERLAY_COLOURS.length) throw new Error(`URL parameter 'overlay': at most ${OVERLAY_COLOURS.length} models`);
    return specs.map((spec) => {
      const [model, ...assignments] = spec.split(':');
      if (!modelInfo(model)) throw new Error(`URL parameter 'overlay': unknown model '${model}' (models: ${models.map((m) => m.name).join(', ')})`);
      const params = {};
      for (const a of assignments) {
        const eq = a.indexOf('=');
        if (eq <= 0) throw new Error(`URL parameter 'overlay': '${a}' in '${spec}' is not name=value`);
        params[a.slice(0, eq)] = a.slice(eq + 1);
      }
      const probe = call({ op: 'eval', model, params, wi: [0, 0, 1], wo: [0, 0, 1] });
      if (probe.error) throw new Error(`URL parameter 'overlay': ${spec}: ${probe.error}`);
      return { model, params };
    });
  }

  function overlaySpec(model, params) {
    return [model, ...Object.entries(params).map(([k, v]) => `${k}=${v}`)].join(':');
  }

  function queryFromState(s) {
    const q = new URLSearchParams();
    q.set('model', s.model);
    for (const [k, v] of Object.entries(s.params)) q.set(k, v);
    for (const [k, v] of Object.entries(s.view)) q.set(k, v);
    return '?' + q.toString().replace(/%2C/g, ',').replace(/%3A/g, ':').replace(/%3B/g, ';').replace(/%3D/g, '=');
  }

  // ---- controls ---------------------------------------------------------------------------------------
  function sliderMapping(p) {
    // A log slider for wide positive ranges (exponents up to 1e6), linear otherwise.
    const log = p.min >= 0 && p.max > 1000;
    return log
      ? { to: (v) => Math.log10(v + 1) / Math.log10(p.max + 1), from: (t) => Math.pow(10, t * Math.log10(p.max + 1)) - 1 }
      : { to: (v) => (v - p.min) / (p.max - p.min), from: (t) => p.min + t * (p.max - p.min) };
  }

  function buildParamControls() {
    const form = $('shadelab-params');
    form.textContent = '';
    const info = modelInfo(state.model);
    $('shadelab-formula').textContent = `f_r = ${info.formula}  (${info.source})`;
    for (const p of info.params) {
      const row = document.createElement('div');
      row.className = 'param';
      row.title = p.description;
      const label = document.createElement('label');
      label.textContent = p.name;
      row.appendChild(label);
      let field;
      if (p.kind === 'choice') {
        field = document.createElement('select');
        for (const c of p.choices) { const o = document.createElement('option'); o.textContent = c; field.appendChild(o); }
        field.value = effective(p.name);
        field.addEventListener('change', () => { setParam(p.name, field.value); changed(); });
        row.appendChild(field);
        row.appendChild(document.createElement('span'));
      } else {
        const slider = document.createElement('input');
        slider.type = 'range'; slider.min = 0; slider.max = 1000; slider.step = 1;
        field = document.createElement('input');
        field.type = 'text';
        field.value = effective(p.name);
        const map = sliderMapping(p);
        const first = Number(String(field.value).split(/[,;]/)[0]);
        slider.value = Number.isFinite(first) ? Math.round(1000 * map.to(first)) : 0;
        slider.disabled = p.kind !== 'scalar';
        slider.addEventListener('input', () => {
          const v = map.from(slider.value / 1000);
          field.value = String(Number(v.toPrecision(4)));
          errors = [];
          const e = setParam(p.name, field.value);
          if (e) errors = [e];
          showErrors();
          changed();
        });
        field.addEventListener('change', () => {
          const e = setParam(p.name, field.value);
          errors = e ? [e] : [];
          showErrors();
          if (!e) changed();
        });
        field.id = `shadelab-param-${p.name}`;
        slider.id = `shadelab-slider-${p.name}`;
        row.appendChild(slider);
        row.appendChild(field);
      }
      form.appendChild(row);
    }
  }

  const VIEW_FIELDS = { theta: 'shadelab-theta', wi: 'shadelab-wi', wo: 'shadelab-wo', theta_in: 'shadelab-theta-in',
                        fixed: 'shadelab-fixed', scale: 'shadelab-scale', units: 'shadelab-units', light_pos: 'shadelab-light-pos',
                        light: 'shadelab-light', exposure: 'shadelab-exposure', tone: 'shadelab-tone',
                        lighting: 'shadelab-lighting', env: 'shadelab-env', overlay: 'shadelab-overlay' };

  function syncViewControls() {
    $('shadelab-model').value = state.model;
    for (const [key, id] of Object.entries(VIEW_FIELDS)) $(id).value = state.view[key];
    $('shadelab-cos').checked = state.view.cos === '1';
  }

  function buildViewControls() {
    const envSelect = $('shadelab-env');
    for (const name of ENVIRONMENTS.names) { const o = document.createElement('option'); o.textContent = name; envSelect.appendChild(o); }
    if (ENVIRONMENTS.names.length === 0) {
      const o = document.createElement('option'); o.textContent = VIEW_DEFAULTS.env; envSelect.appendChild(o);
      envSelect.disabled = true;
    }
    $('shadelab-env-status').textContent = ENVIRONMENTS.names.length > 0
      ? `${ENVIRONMENTS.names.length} HDRIs baked by shadelab at ${ENVIRONMENTS.size} x ${ENVIRONMENTS.size} from ${ENVIRONMENTS.dir}`
      : ENVIRONMENTS.message;
    const select = $('shadelab-model');
    for (const m of models) { const o = document.createElement('option'); o.textContent = m.name; select.appendChild(o); }
    select.addEventListener('change', () => {
      const info = modelInfo(select.value);
      state.model = info.name;
      state.params = {};
      buildParamControls();
      changed();
    });
    for (const [key, id] of Object.entries(VIEW_FIELDS)) {
      $(id).addEventListener(key === 'exposure' ? 'input' : 'change', () => {
        const trial = Object.assign({}, state.view, { [key]: $(id).value });
        const parsed = stateFromQuery(queryFromState({ model: state.model, params: state.params, view: trial }));
        errors = parsed.problems;
        showErrors();
        if (errors.length === 0) { state.view = parsed.state.view; changed(); }
      });
    }
    $('shadelab-overlay-add').addEventListener('click', () => {
      const spec = overlaySpec(state.model, state.params);
      const list = state.view.overlay === '' ? [] : state.view.overlay.split(';');
      if (list.length >= OVERLAY_COLOURS.length) list.shift();
      list.push(spec);
      state.view.overlay = list.join(';');
      $('shadelab-overlay').value = state.view.overlay;
      changed();
    });
    $('shadelab-overlay-clear').addEventListener('click', () => { state.view.overlay = ''; $('shadelab-overlay').value = ''; changed(); });
    $('shadelab-cos').addEventListener('change', () => { state.view.cos = $('shadelab-cos').checked ? '1' : '0'; changed(); });
    $('shadelab-export').addEventListener('click', () => {
      const lang = $('shadelab-export-lang').value;
      const r = call({ op: 'shader', model: state.model, params: state.params, lang });
      const text = r.error ? r.error : r.text;
      const pre = $('shadelab-export-text');
      pre.hidden = false;
      pre.textContent = text;
      if (!r.error) {
        const a = document.createElement('a');
        a.href = URL.createObjectURL(new Blob([text], { type: 'text/plain' }));
        a.download = `${state.model}.${lang === 'hlsl' ? 'hlsl' : lang === 'essl' ? 'essl.glsl' : 'glsl'}`;
        document.body.appendChild(a);
        a.click();
        a.remove();
      }
    });
  }

  // ---- drawing (no formulas: the values are the library's) ------------------------------------------
  function axes(ctx, w, h) {
    ctx.clearRect(0, 0, w, h);
    ctx.fillStyle = '#fff'; ctx.fillRect(0, 0, w, h);
    ctx.strokeStyle = '#bbb'; ctx.lineWidth = 1;
  }

  function scaleValue(v, max, log) {
    if (!log) return max > 0 ? v / max : 0;
    const lo = Math.log10(max) - 4;  // four decades
    return v > 0 ? Math.max(0, (Math.log10(v) - lo) / 4) : 0;
  }

  function drawLobe(lobe, overlays) {
    const c = $('shadelab-lobe'); const ctx = c.getContext('2d');
    axes(ctx, c.width, c.height);
    const ox = c.width / 2, oy = c.height - 12, r = Math.min(ox, oy) - 8;
    ctx.beginPath(); ctx.moveTo(8, oy); ctx.lineTo(c.width - 8, oy); ctx.stroke();
    ctx.beginPath(); ctx.arc(ox, oy, r, Math.PI, 0); ctx.stroke();
    const max = Math.max(...lobe.luminance, ...overlays.flatMap((o) => o.lobe.luminance));
    const log = state.view.scale === 'log';
    overlays.forEach((o, k) => {
      ctx.strokeStyle = OVERLAY_COLOURS[k]; ctx.lineWidth = 1.5; ctx.beginPath();
      o.lobe.angle.forEach((a, i) => {
        const s = r * scaleValue(o.lobe.luminance[i], max, log);
        const x = ox + s * Math.sin(a * Math.PI / 180), y = oy - s * Math.cos(a * Math.PI / 180);
        if (i === 0) ctx.moveTo(x, y); else ctx.lineTo(x, y);
      });
      ctx.stroke();
      ctx.fillStyle = OVERLAY_COLOURS[k]; ctx.font = '11px sans-serif';
      ctx.fillText(o.model, c.width - 150, 14 + 13 * k);
    });
    ctx.strokeStyle = '#bbb'; ctx.lineWidth = 1;
    const fixedAngle = -Number(state.view.theta_in) * Math.PI / 180;
    ctx.strokeStyle = '#e65100';
    ctx.beginPath(); ctx.moveTo(ox, oy); ctx.lineTo(ox + r * Math.sin(fixedAngle), oy - r * Math.cos(fixedAngle)); ctx.stroke();
    ctx.strokeStyle = '#1565c0'; ctx.lineWidth = 2; ctx.beginPath();
    lobe.angle.forEach((a, i) => {
      const s = r * scaleValue(lobe.luminance[i], max, log);
      const x = ox + s * Math.sin(a * Math.PI / 180), y = oy - s * Math.cos(a * Math.PI / 180);
      if (i === 0) ctx.moveTo(x, y); else ctx.lineTo(x, y);
    });
    ctx.stroke();
    ctx.fillStyle = '#333'; ctx.font = '11px sans-serif';
    ctx.fillText(`max ${max.toPrecision(4)} 1/sr (${log ? 'log, 4 decades' : 'linear'})`, 8, 14);
  }

  function drawLobe3d(grid) {
    const c = $('shadelab-lobe3d'); const ctx = c.getContext('2d');
    axes(ctx, c.width, c.height);
    const max = Math.max(...grid.luminance.flat());
    const log = state.view.scale === 'log';
    const ox = c.width / 2, oy = c.height * 0.8, r = c.height * 0.7;
    // An oblique view: x right, z up, y into the page (tilted by 30 degrees).
    const project = (t, p, s) => {
      const x = Math.sin(t) * Math.cos(p) * s, y = Math.sin(t) * Math.sin(p) * s, z = Math.cos(t) * s;
      return [ox + r * (x + 0.35 * y), oy - r * (z + 0.35 * y * 0.5)];
    };
    ctx.strokeStyle = '#1565c0'; ctx.lineWidth = 0.7;
    const nt = grid.n_theta, np = grid.n_phi;
    for (let i = 0; i < nt; ++i) {
      ctx.beginPath();
      for (let j = 0; j <= np; ++j) {
        const t = (Math.PI / 2) * i / (nt - 1), p = 2 * Math.PI * (j % np) / np;
        const [x, y] = project(t, p, scaleValue(grid.luminance[i][j % np], max, log));
        if (j === 0) ctx.moveTo(x, y); else ctx.lineTo(x, y);
      }
      ctx.stroke();
    }
    for (let j = 0; j < np; j += 2) {
      ctx.beginPath();
      for (let i = 0; i < nt; ++i) {
        const t = (Math.PI / 2) * i / (nt - 1), p = 2 * Math.PI * j / np;
        const [x, y] = project(t, p, scaleValue(grid.luminance[i][j], max, log));
        if (i === 0) ctx.moveTo(x, y); else ctx.lineTo(x, y);
      }
      ctx.stroke();
    }
  }

  function drawAlbedo(curve, overlays) {
    const c = $('shadelab-albedo'); const ctx = c.getContext('2d');
    axes(ctx, c.width, c.height);
    const x0 = 30, y0 = c.height - 20, w = c.width - 40, h = c.height - 40;
    const top = Math.max(1.1, ...curve.albedo.flat(), ...overlays.flatMap((o) => o.albedo_curve.albedo.flat())) * 1.05;
    // Each overlaid model: its r, g, b curves in its colour, dashed 6/2, 2/2 and 1/1.
    overlays.forEach((o, m) => {
      ctx.strokeStyle = OVERLAY_COLOURS[m]; ctx.lineWidth = 1;
      [[6, 2], [2, 2], [1, 1]].forEach((dash, k) => {
        ctx.setLineDash(dash); ctx.beginPath();
        o.albedo_curve.theta.forEach((t, i) => {
          const x = x0 + w * t / 90, y = y0 - h * o.albedo_curve.albedo[i][k] / top;
          if (i === 0) ctx.moveTo(x, y); else ctx.lineTo(x, y);
        });
        ctx.stroke();
      });
      ctx.setLineDash([]);
      ctx.fillStyle = OVERLAY_COLOURS[m]; ctx.font = '11px sans-serif';
      ctx.fillText(o.model, x0 + w - 150, 14 + 13 * m);
    });
    ctx.strokeStyle = '#bbb';
    ctx.beginPath(); ctx.moveTo(x0, y0 - h); ctx.lineTo(x0, y0); ctx.lineTo(x0 + w, y0); ctx.stroke();
    ctx.setLineDash([4, 3]); ctx.strokeStyle = '#000';
    ctx.beginPath(); ctx.moveTo(x0, y0 - h / top); ctx.lineTo(x0 + w, y0 - h / top); ctx.stroke();
    ctx.setLineDash([]);
    ['#c62828', '#2e7d32', '#1565c0'].forEach((colour, k) => {
      ctx.strokeStyle = colour; ctx.lineWidth = 1.5; ctx.beginPath();
      curve.theta.forEach((t, i) => {
        const x = x0 + w * t / 90, y = y0 - h * curve.albedo[i][k] / top;
        if (i === 0) ctx.moveTo(x, y); else ctx.lineTo(x, y);
      });
      ctx.stroke();
    });
    ctx.fillStyle = '#333'; ctx.font = '11px sans-serif';
    ctx.fillText('1 (energy)', x0 + 4, y0 - h / top - 3);
    ctx.fillText('theta_o (deg) 0 .. 90', x0 + w - 110, y0 + 14);
  }

  function fillTables(albedo, probe, zoo) {
    const t = $('shadelab-albedo-table');
    t.innerHTML = '<tr><th>theta</th><th>albedo r</th><th>g</th><th>b</th></tr>';
    albedo.theta.forEach((th, i) => {
      const tr = t.insertRow();
      [th, ...albedo.albedo[i]].forEach((v) => { tr.insertCell().textContent = String(v); });
    });
    $('shadelab-probe').textContent = `f_r(wi = ${probe.wi.join(', ')}; wo = ${probe.wo.join(', ')}) = ${probe.f.join(', ')} 1/sr`;
    const z = $('shadelab-zoo');
    z.innerHTML = `<caption>the normalization zoo at n = ${zoo.n}</caption><tr><th class="text">model</th><th class="text">closed form</th>` +
      '<th>closed value</th><th>numeric</th><th>rel. error</th><th>bounds</th></tr>';
    for (const r of zoo.rows) {
      const tr = z.insertRow();
      tr.insertCell().textContent = r.model; tr.cells[0].className = 'text';
      tr.insertCell().textContent = r.closed_form; tr.cells[1].className = 'text';
      tr.insertCell().textContent = r.closed_form_value.toPrecision(9);
      tr.insertCell().textContent = r.numeric.toPrecision(9);
      tr.insertCell().textContent = r.relative_error.toExponential(1);
      tr.insertCell().textContent = r.lower !== null ? `${r.lower.toPrecision(6)} .. ${r.upper.toPrecision(6)}` : '-';
    }
  }

  // ---- the sphere: the exported GLSL ES in WebGL 2 ------------------------------------------------------
  let gl = null, program = null, programSource = '', sphereError = '';
  let displayKernels = null;
  const MAX_BLOCKS = 24;
  let tablesBuffer = null;
  const envTextures = {};  // name -> WebGL texture
  const envLoads = {};     // name -> 'loading' | 'loaded' | error message

  // env-NAME.js, by a script element (works from file://); calls done() when it has run or failed.
  function loadEnvironment(name, done) {
    const data = window.shadelabEnvironmentData;
    if (data && data[name]) { envLoads[name] = 'loaded'; done(); return; }
    if (envLoads[name] === 'loading') return;
    envLoads[name] = 'loading';
    const script = document.createElement('script');
    script.src = `env-${name}.js`;
    script.onload = () => {
      const d = window.shadelabEnvironmentData;
      envLoads[name] = d && d[name] ? 'loaded' : `HDRI '${name}': env-${name}.js has no data`;
      done();
    };
    script.onerror = () => { envLoads[name] = `HDRI '${name}': env-${name}.js did not load`; done(); };
    document.head.appendChild(script);
  }

  // An n x n RGBA32F table (the split sum's DFG and lobe tables of env-NAME.js), read with texelFetch.
  function tableTexture(key, n, b64) {
    if (envTextures[key]) return envTextures[key];
    const bytes = Uint8Array.from(atob(b64), (c) => c.charCodeAt(0));
    const tex = gl.createTexture();
    gl.bindTexture(gl.TEXTURE_2D, tex);
    gl.texImage2D(gl.TEXTURE_2D, 0, gl.RGBA32F, n, n, 0, gl.RGBA, gl.FLOAT, new Float32Array(bytes.buffer));
    gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_MIN_FILTER, gl.NEAREST);
    gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_MAG_FILTER, gl.NEAREST);
    envTextures[key] = tex;
    return tex;
  }

  function environmentTexture(env) {
    if (envTextures[env.name]) return envTextures[env.name];
    const bytes = Uint8Array.from(atob(env.texels), (c) => c.charCodeAt(0));
    const texels = new Float32Array(bytes.buffer);
    const tex = gl.createTexture();
    gl.activeTexture(gl.TEXTURE0);
    gl.bindTexture(gl.TEXTURE_2D, tex);
    gl.pixelStorei(gl.UNPACK_ALIGNMENT, 4);
    gl.texImage2D(gl.TEXTURE_2D, 0, gl.RGB32F, env.width, env.height, 0, gl.RGB, gl.FLOAT, texels);
    gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_MIN_FILTER, gl.NEAREST);
    gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_MAG_FILTER, gl.NEAREST);
    gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_WRAP_S, gl.CLAMP_TO_EDGE);
    gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_WRAP_T, gl.CLAMP_TO_EDGE);
    envTextures[env.name] = tex;
    return tex;
  }

  const VERTEX = `#version 300 es
in vec2 p;
void main() { gl_Position = vec4(p, 0.0, 1.0); }
`;

  // The texel fetches the exported split sum calls (export.h ibl_fetch_declarations; kernels.h), here over the
  // page's environment texture (the GGX chain's levels are its blocks from u_ggx_first on) and the two tables.
  const IBL_FETCHES = `#define SHADELAB_IBL_FETCHES
uniform int u_ggx_first;
uniform highp sampler2D u_dfg, u_lobes;
int cube_size(int cube) { return u_block_size[u_ggx_first + cube]; }
vec3 cube_texel(int cube, int face, int x, int y) { return env_texel(u_ggx_first + cube, face, x, y); }
float dfg_texel(int x, int y, int channel) { return texelFetch(u_dfg, ivec2(x, y), 0)[channel]; }
int shadelab_dfg_size() { return textureSize(u_dfg, 0).x; }
float split_sum_lobe_texel(int x, int y, int channel) { return texelFetch(u_lobes, ivec2(x, y), 0)[channel]; }
int shadelab_split_sum_lobe_size() { return textureSize(u_lobes, 0).x; }
`;

  function fragmentSource(modelText, entry, iblEntry) {
    // The exported model (its kernels, the punctual term in both unit conventions and the inverse-square law
    // of kernels/game_shading.sl; for the split-sum models with an HDRI, `shader --ibl`'s environment lighting,
    // kernels/game_ibl.sl) and kernels/display.sl; the rest is the camera and sphere geometry.
    return `#version 300 es
precision highp float;
precision highp int;
// The baked HDRI (env-NAME.js): block 0 the radiance cube, block 1 + i the prefiltered level i, then the GGX
// chain's levels, as rows of u_env.
uniform highp sampler2D u_env;
uniform int u_block_size[${MAX_BLOCKS}], u_block_row[${MAX_BLOCKS}];
vec3 env_texel(int block, int face, int x, int y) {
  return texelFetch(u_env, ivec2(x, u_block_row[block] + face * u_block_size[block] + y), 0).rgb;
}
${iblEntry ? IBL_FETCHES : ''}
${modelText}
${displayKernels}
uniform vec2 u_size;
uniform vec3 u_eye, u_forward, u_right, u_up;
uniform float u_tan_half;
uniform int u_spp_side;
uniform vec3 u_light_pos, u_light;
uniform int u_units;
uniform float u_exposure;
uniform int u_view;
uniform int u_point_on, u_env_on;
uniform int u_levels, u_ggx_levels, u_ggx_mapping;
uniform float u_gloss_scale, u_gloss_bias;
uniform Sh9Coefficients u_sh;
// The material's game lobe (brdf/game_lobe.h, the module's game_lobe answer).
uniform GameSpecularAlbedo u_rho_s;
uniform vec3 u_kd;
uniform float u_exponent, u_wrap;
out vec4 o_colour;

// A cube map lookup as CubeMap::sample (envmap/base/cubemap.h: the face of OpenGL table 8.19, ties to X then Y,
// bilinear between texel centres, clamped at the face's edges); the browser test proves it equal to the C++.
vec3 cube_sample(int block, vec3 r) {
  vec3 a = abs(r);
  int face;
  float sc, tc, ma;
  if (a.x >= a.y && a.x >= a.z) {
    ma = a.x;
    if (r.x >= 0.0) { face = 0; sc = -r.z; tc = -r.y; } else { face = 1; sc = r.z; tc = -r.y; }
  } else if (a.y >= a.z) {
    ma = a.y;
    if (r.y >= 0.0) { face = 2; sc = r.x; tc = r.z; } else { face = 3; sc = r.x; tc = -r.z; }
  } else {
    ma = a.z;
    if (r.z >= 0.0) { face = 4; sc = r.x; tc = -r.y; } else { face = 5; sc = -r.x; tc = -r.y; }
  }
  int size = u_block_size[block];
  float n = float(size);
  float fx = clamp(0.5 * (sc / ma + 1.0) * n - 0.5, 0.0, n - 1.0);
  float fy = clamp(0.5 * (tc / ma + 1.0) * n - 0.5, 0.0, n - 1.0);
  int x0 = min(int(fx), size - 1), y0 = min(int(fy), size - 1);
  int x1 = min(x0 + 1, size - 1), y1 = min(y0 + 1, size - 1);
  float ax = fx - float(x0), ay = fy - float(y0);
  return (env_texel(block, face, x0, y0) * (1.0 - ax) + env_texel(block, face, x1, y0) * ax) * (1.0 - ay) +
         (env_texel(block, face, x0, y1) * (1.0 - ax) + env_texel(block, face, x1, y1) * ax) * ay;
}

// The prefiltered radiance for a Phong exponent: the chain's level for it (game_prefiltered_level), linear
// between levels, as the game renderer's prefiltered() (render/game_renderer.cpp).
vec3 prefiltered(vec3 r, float n_phong) {
  float level = game_prefiltered_level(n_phong, float(u_levels), u_gloss_scale, u_gloss_bias);
  int i0 = int(level);
  int i1 = min(i0 + 1, u_levels - 1);
  float t = level - float(i0);
  return cube_sample(1 + i0, r) * (1.0 - t) + cube_sample(1 + i1, r) * t;
}

// The radiance along a camera ray: the sphere (centre 0, radius ${SPHERE.radius.toFixed(1)}) under the point light and/or the
// HDRI (the game shading equation of render/game_renderer.cpp with the kernels it uses), the HDRI's radiance cube
// behind (black without it).
vec3 radiance(vec3 d) {
  vec3 behind = u_env_on == 1 ? cube_sample(0, d) : vec3(0.0);
  float b = dot(u_eye, d);
  float c = dot(u_eye, u_eye) - ${(SPHERE.radius * SPHERE.radius).toFixed(1)};
  float disc = b * b - c;
  if (disc < 0.0) return behind;
  float t = -b - sqrt(disc);
  if (t <= 0.0) return behind;
  vec3 n = normalize(u_eye + d * t);
  vec3 pos = n * ${SPHERE.radius.toFixed(1)};
  // The renderer's frame on a sphere (render/accel.cpp, materials.cpp): tangent along (-n.z, 0, n.x).
  vec3 s = vec3(-n.z, 0.0, n.x);
  s = length(s) > 1.0e-6 ? normalize(s) : vec3(1.0, 0.0, 0.0);
  vec3 tb = cross(n, s);
  mat3 to_local = transpose(mat3(s, tb, n));
  vec3 wo = to_local * (-d);
  vec3 l = vec3(0.0);
  vec3 to_light = u_light_pos - pos;
  float d2 = dot(to_light, to_light);
  if (u_point_on == 1 && d2 > 0.0) {
    vec3 wi = to_local * normalize(to_light);
    vec3 e = point_light_irradiance(u_light, d2);
    l += u_units == 0 ? ${entry}_punctual_game(wi, wo, e) : ${entry}_punctual_radiometric(wi, wo, e);
  }
  if (u_env_on == 1) {
${iblEntry ? `    // SH9 diffuse and the split sum, the exported text (render --mode game's default for this model).
    l += ${iblEntry}(n, -d, u_sh, u_ggx_levels, u_ggx_mapping);
    return l;` : ''}
    // Diffuse ambient from SH9 (wrapped band factors for wrapped diffuse), specular ambient rho_s x prefiltered.
    vec3 e_over_pi = u_wrap > 0.0 ? sh9_irradiance_game_wrapped(u_sh, n, u_wrap) : sh9_irradiance_game(u_sh, n);
    l += game_diffuse_ambient(u_kd, e_over_pi);
    if (u_exponent > 0.0) {
      vec3 r = game_reflect(-d, n);
      l += game_specular_ambient(game_specular_albedo(u_rho_s, wo.z), prefiltered(r, u_exponent));
    }
  }
  return l;
}

// The view transform of kernels/display.sl after the exposure, then the 8-bit sRGB code.
vec3 display(vec3 l) {
  vec3 d = view_transform(u_view, u_exposure, l);
  return vec3(srgb8_code(d.r), srgb8_code(d.g), srgb8_code(d.b)) / 255.0;
}

void main() {
  // Pixel (x, y) counted from the top-left, as the renderer's image; spp_side^2 stratified sub-pixels.
  float x = floor(gl_FragCoord.x), y = u_size.y - 1.0 - floor(gl_FragCoord.y);
  vec3 sum = vec3(0.0);
  for (int j = 0; j < u_spp_side; ++j) {
    for (int i = 0; i < u_spp_side; ++i) {
      float px = x + (float(i) + 0.5) / float(u_spp_side);
      float py = y + (float(j) + 0.5) / float(u_spp_side);
      float sx = (2.0 * px / u_size.x - 1.0) * u_tan_half * (u_size.x / u_size.y);
      float sy = (1.0 - 2.0 * py / u_size.y) * u_tan_half;
      sum += radiance(normalize(u_forward + u_right * sx + u_up * sy));
    }
  }
  vec3 l = sum / float(u_spp_side * u_spp_side);
  o_colour = vec4(display(l), 1.0);
}
`;
  }

  function compile(type, source) {
    const sh = gl.createShader(type);
    gl.shaderSource(sh, source);
    gl.compileShader(sh);
    if (!gl.getShaderParameter(sh, gl.COMPILE_STATUS)) throw new Error('WebGL 2 shader: ' + gl.getShaderInfoLog(sh));
    return sh;
  }

  function sub(a, b) { return [a[0] - b[0], a[1] - b[1], a[2] - b[2]]; }
  function cross3(a, b) { return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]; }
  function unit(a) { const l = Math.hypot(...a); return a.map((x) => x / l); }

  function drawSphere() {
    const canvas = $('shadelab-sphere');
    if (!gl) {
      gl = canvas.getContext('webgl2', { preserveDrawingBuffer: true, antialias: false });
      if (!gl) { sphereError = 'WebGL 2 is not available'; return; }
      const buf = gl.createBuffer();
      gl.bindBuffer(gl.ARRAY_BUFFER, buf);
      gl.bufferData(gl.ARRAY_BUFFER, new Float32Array([-1, -1, 3, -1, -1, 3]), gl.STATIC_DRAW);
      displayKernels = call({ op: 'kernels', names: ['srgb8_code', 'view_transform', 'exposure_scale', 'game_specular_albedo',
                                                     'game_prefiltered_level', 'game_reflect', 'game_diffuse_ambient',
                                                     'game_specular_ambient'], lang: 'essl' }).text;
    }
    const lighting = state.view.lighting;
    const env = lighting === 'point' ? null : (window.shadelabEnvironmentData || {})[state.view.env] || null;
    const lobe = call({ op: 'game_lobe', model: state.model, params: state.params });
    if (lobe.error) throw new Error(lobe.error);
    // The split-sum models under an HDRI: the exported environment lighting (`shader MODEL --ibl`).
    const splitSum = !!(env && lobe.split_sum && env.split_sum);
    const ex = call({ op: 'shader', model: state.model, params: state.params, lang: 'essl', ibl: splitSum });
    if (ex.error) { sphereError = ex.error; return; }
    const source = fragmentSource(ex.text, ex.entry, splitSum ? ex.ibl_entry : '');
    if (source !== programSource) {
      const p = gl.createProgram();
      gl.attachShader(p, compile(gl.VERTEX_SHADER, VERTEX));
      gl.attachShader(p, compile(gl.FRAGMENT_SHADER, source));
      gl.bindAttribLocation(p, 0, 'p');
      gl.linkProgram(p);
      if (!gl.getProgramParameter(p, gl.LINK_STATUS)) throw new Error('WebGL 2 link: ' + gl.getProgramInfoLog(p));
      if (program) gl.deleteProgram(program);
      program = p;
      programSource = source;
    }
    gl.useProgram(program);
    gl.viewport(0, 0, canvas.width, canvas.height);
    gl.enableVertexAttribArray(0);
    gl.vertexAttribPointer(0, 2, gl.FLOAT, false, 0, 0);
    const cam = SPHERE.camera;
    const forward = unit(sub(cam.look_at, cam.position));
    const right = unit(cross3(forward, cam.up));
    const up = cross3(right, forward);
    const u = (name) => gl.getUniformLocation(program, name);
    gl.uniform2f(u('u_size'), canvas.width, canvas.height);
    gl.uniform3fv(u('u_eye'), cam.position);
    gl.uniform3fv(u('u_forward'), forward);
    gl.uniform3fv(u('u_right'), right);
    gl.uniform3fv(u('u_up'), up);
    gl.uniform1f(u('u_tan_half'), Math.tan(0.5 * cam.fov * Math.PI / 180));
    gl.uniform1i(u('u_spp_side'), Math.round(Math.sqrt(SPHERE.spp)));
    gl.uniform3fv(u('u_light_pos'), numbers(state.view.light_pos, 3, 'light_pos'));
    const lv = numbers(state.view.light, 0, 'light');
    gl.uniform3fv(u('u_light'), lv.length === 1 ? [lv[0], lv[0], lv[0]] : lv);
    gl.uniform1i(u('u_units'), state.view.units === 'game' ? 0 : 1);
    gl.uniform1f(u('u_exposure'), Number(state.view.exposure));
    gl.uniform1i(u('u_view'), TONE_VIEWS[state.view.tone]);
    gl.uniform1i(u('u_point_on'), lighting !== 'hdri' || !env ? 1 : 0);
    gl.uniform1i(u('u_env_on'), env ? 1 : 0);
    gl.uniform3fv(u('u_rho_s.bin[0]'), lobe.specular_albedo.flat());
    gl.uniform3fv(u('u_kd'), lobe.diffuse_albedo);
    gl.uniform1f(u('u_exponent'), lobe.exponent);
    gl.uniform1f(u('u_wrap'), lobe.wrap);
    if (env) {
      if (env.blocks.length > MAX_BLOCKS) throw new Error(`HDRI '${env.name}': ${env.blocks.length} cube blocks, the shader takes ${MAX_BLOCKS}`);
      gl.activeTexture(gl.TEXTURE0);
      gl.bindTexture(gl.TEXTURE_2D, environmentTexture(env));
      gl.uniform1i(u('u_env'), 0);
      const sizes = new Int32Array(MAX_BLOCKS), rows = new Int32Array(MAX_BLOCKS);
      env.blocks.forEach((b, i) => { sizes[i] = b.size; rows[i] = b.row; });
      gl.uniform1iv(u('u_block_size[0]'), sizes);
      gl.uniform1iv(u('u_block_row[0]'), rows);
      gl.uniform1i(u('u_levels'), (env.split_sum ? env.split_sum.ggx_first_block : env.blocks.length) - 1);  // the Phong chain's
      gl.uniform1f(u('u_gloss_scale'), env.gloss_scale);
      gl.uniform1f(u('u_gloss_bias'), env.gloss_bias);
      gl.uniform3fv(u('u_sh.c[0]'), env.sh.flat());
      if (splitSum) {
        const ss = env.split_sum;
        gl.uniform1i(u('u_ggx_first'), ss.ggx_first_block);
        gl.uniform1i(u('u_ggx_levels'), ss.ggx_levels);
        gl.uniform1i(u('u_ggx_mapping'), ss.ggx_mapping === 'filament' ? 1 : 0);  // GGX_MIP_MAPPING_*
        gl.activeTexture(gl.TEXTURE2);
        gl.bindTexture(gl.TEXTURE_2D, tableTexture(env.name + ':dfg', ss.dfg_size, ss.dfg));
        gl.uniform1i(u('u_dfg'), 2);
        gl.activeTexture(gl.TEXTURE3);
        gl.bindTexture(gl.TEXTURE_2D, tableTexture(env.name + ':lobes', ss.lobe_size, ss.lobes));
        gl.uniform1i(u('u_lobes'), 3);
        gl.activeTexture(gl.TEXTURE0);
      }
    }
    if (ex.tables_block) {
      // The GGX energy tables' uniform block (the bytes `shadelab shader --tables-out` writes), binding point 1.
      const index = gl.getUniformBlockIndex(program, ex.tables_block);
      if (index !== gl.INVALID_INDEX) {
        if (!tablesBuffer) tablesBuffer = gl.createBuffer();
        gl.bindBuffer(gl.UNIFORM_BUFFER, tablesBuffer);
        gl.bufferData(gl.UNIFORM_BUFFER, new Uint8Array(ex.tables), gl.STATIC_DRAW);
        gl.uniformBlockBinding(program, index, 1);
        gl.bindBufferBase(gl.UNIFORM_BUFFER, 1, tablesBuffer);
      }
    }
    gl.drawArrays(gl.TRIANGLES, 0, 3);
    sphereError = '';
  }

  // The sphere's pixels, top row first, RGBA 0..255 (for tests and scripts).
  window.shadelabSpherePixels = function () {
    const w = gl.drawingBufferWidth, h = gl.drawingBufferHeight;
    const raw = new Uint8Array(w * h * 4);
    gl.readPixels(0, 0, w, h, gl.RGBA, gl.UNSIGNED_BYTE, raw);
    const out = new Array(w * h * 4);
    for (let y = 0; y < h; ++y) for (let x = 0; x < w * 4; ++x) out[y * w * 4 + x] = raw[(h - 1 - y) * w * 4 + x];
    return { width: w, height: h, rgba: out };
  };

  // ---- update ---------------------------------------------------------------------------------------------
  let pending = false;
  function changed() {
    if (pending) return;
    pending = true;
    requestAnimationFrame(() => { pending = false; update(); });
  }

  function update() {
    const t0 = performance.now();
    const v = state.view;
    // The HDRI's data first (a script load); the update runs again when it is there.
    if (v.lighting !== 'point' && envLoads[v.env] !== 'loaded' && !(envLoads[v.env] || '').startsWith('HDRI')) {
      loadEnvironment(v.env, changed);
      return;
    }
    const envProblem = v.lighting !== 'point' && envLoads[v.env] !== 'loaded' ? envLoads[v.env] : null;
    const theta = numbers(v.theta, 0, 'theta');
    const wi = numbers(v.wi, 3, 'wi'), wo = numbers(v.wo, 3, 'wo');
    const base = { model: state.model, params: state.params };
    const probe = call(Object.assign({ op: 'eval', wi, wo }, base));
    const albedo = call(Object.assign({ op: 'albedo', theta }, base));
    const curve = call(Object.assign({ op: 'albedo', theta: ALBEDO_CURVE }, base));
    const thetaIn = Number(v.theta_in);
    const lobe = call(Object.assign({ op: 'lobe', theta_in: thetaIn, times_cos: v.cos === '1', fixed: v.fixed, samples: 361 }, base));
    const a = -thetaIn * Math.PI / 180;
    const lobe3dWi = [Math.sin(a), 0, Math.cos(a)];
    const lobe3d = call(Object.assign({ op: 'lobe3d', wi: lobe3dWi, n_theta: 19, n_phi: 36 }, base));
    const info = modelInfo(state.model);
    const nParam = info.params.find((p) => p.name === 'n' && p.kind === 'scalar');
    const zooN = nParam ? Number(effective('n')) : 100;
    const zoo = call({ op: 'zoo', n: zooN });
    const overlays = parseOverlay(v.overlay).map((o) => {
      const b = { model: o.model, params: o.params };
      const oc = call(Object.assign({ op: 'albedo', theta: ALBEDO_CURVE }, b));
      const ol = call(Object.assign({ op: 'lobe', theta_in: thetaIn, times_cos: v.cos === '1', fixed: v.fixed, samples: 361 }, b));
      return { model: o.model, params: o.params, albedo_curve: oc, lobe: ol };
    });
    const failed = [probe, albedo, curve, lobe, lobe3d, zoo, ...overlays.flatMap((o) => [o.albedo_curve, o.lobe])].find((r) => r.error);
    if (failed) {
      // Still a state (with the error) and the ready mark: a script waiting on the page is told.
      errors = [failed.error];
      showErrors();
      $('shadelab-state').textContent = JSON.stringify({ model: state.model, params: Object.assign({}, state.params), errors });
      document.body.dataset.ready = String(Number(document.body.dataset.ready || 0) + 1);
      return;
    }
    drawLobe(lobe, overlays);
    drawLobe3d(lobe3d);
    drawAlbedo(curve, overlays);
    const probeState = { wi, wo, f: probe.f };
    fillTables(albedo, probeState, { n: zooN, rows: zoo.rows });
    try { drawSphere(); } catch (e) { sphereError = e.message; }
    if (envProblem && !sphereError) sphereError = envProblem;  // drawn with the point light alone
    if (sphereError) { errors = [sphereError]; showErrors(); }
    const query = queryFromState(state);
    history.replaceState(null, '', query);
    $('shadelab-link').href = query;
    const cam = SPHERE.camera;
    const sphereState = { width: $('shadelab-sphere').width, height: $('shadelab-sphere').height, center: SPHERE.center,
                          radius: SPHERE.radius, camera: cam, spp: SPHERE.spp, units: v.units,
                          light_position: numbers(v.light_pos, 3, 'light_pos'), light: numbers(v.light, 0, 'light'),
                          exposure: Number(v.exposure), tone: v.tone, lighting: v.lighting,
                          env: v.lighting === 'point' ? null : v.env,
                          env_file: v.lighting !== 'point' && !envProblem ? window.shadelabEnvironmentData[v.env].file : null,
                          env_size: ENVIRONMENTS.size, specular_size: ENVIRONMENTS.specular_size,
                          environments: ENVIRONMENTS.names.slice(), env_message: ENVIRONMENTS.message,
                          error: sphereError || null };
    const figures = {
      model: state.model, params: Object.assign({}, state.params),
      all_params: Object.fromEntries(info.params.map((p) => [p.name, effective(p.name)])), theta: albedo.theta, albedo: albedo.albedo,
      probe: probeState, query, view: Object.assign({}, v),
      albedo_curve: { theta: curve.theta, albedo: curve.albedo },
      overlays: overlays.map((o) => ({ model: o.model, params: o.params, albedo_curve: { theta: o.albedo_curve.theta, albedo: o.albedo_curve.albedo },
                                       lobe: { angle: o.lobe.angle, luminance: o.lobe.luminance } })),
      lobe: { theta_in: thetaIn, fixed: v.fixed, times_cos: v.cos === '1', angle: lobe.angle, luminance: lobe.luminance },
      // The 3D lobe as drawn: luminance[i][j] = luminance of f_r(wi, wo), theta_o = 90 i / (n_theta - 1) degrees,
      // phi_o = 360 j / n_phi degrees (the module's lobe3d answer).
      lobe3d: { theta_in: thetaIn, wi: lobe3dWi, n_theta: lobe3d.n_theta, n_phi: lobe3d.n_phi, luminance: lobe3d.luminance },
      zoo: { n: zooN, rows: zoo.rows.map((r) => ({ model: r.model, closed_form_value: r.closed_form_value, numeric: r.numeric,
                                                   relative_error: r.relative_error, lower: r.lower, upper: r.upper })) },
      sphere: sphereState, errors: errors.slice(), update_ms: 0,
    };
    figures.update_ms = Math.round(performance.now() - t0);
    $('shadelab-state').textContent = JSON.stringify(figures);
    $('shadelab-status').textContent = `ready (${figures.update_ms} ms)`;
    document.body.dataset.ready = String(Number(document.body.dataset.ready || 0) + 1);
  }

  async function start() {
    try {
      lib = await createShadelab();
      models = call({ op: 'models' }).models;
      const parsed = stateFromQuery(location.search);
      state = parsed.state;
      errors = parsed.problems;
      showErrors();
      buildViewControls();
      buildParamControls();
      syncViewControls();
      update();
    } catch (e) {
      errors = ['explorer: ' + e.message];
      showErrors();
      $('shadelab-status').textContent = 'failed';
    }
  }

  start();
})();
