// The explorer in a real browser: Debian's headless Chromium (never a downloaded one) driven by
// playwright-core, on the site `shadelab explore --out` writes, loaded from file:// (docs/explorer.md).
//   - the figures in the DOM (#shadelab-state) equal `shadelab brdf albedo/eval --json` to 1e-12 relative
//     (the 3D lobe at a few grid points: the luminance of `brdf eval --json`);
//   - the URL state round-trips (a link reproduces the view, a changed control changes the URL);
//   - a bad URL parameter shows a message naming it, the page still draws; no console error otherwise;
//   - the WebGL 2 sphere (the exported GLSL ES) matches `shadelab render --mode game` of the same scene
//     within a mean absolute difference of 1/255 per channel, after the same display transform.
// Environment: SHADELAB_EXE (the CLI), CHROMIUM (default /usr/bin/chromium), SHADELAB_EXPLORER_SCREENSHOTS
// (a folder: also save the docs' screenshots there).
import { test, before, after } from 'node:test';
import assert from 'node:assert/strict';
import { execFileSync } from 'node:child_process';
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { pathToFileURL } from 'node:url';
import { chromium } from 'playwright-core';

const exe = process.env.SHADELAB_EXE;
if (!exe) throw new Error('SHADELAB_EXE must name the shadelab binary');
const work = fs.mkdtempSync(path.join(os.tmpdir(), 'shadelab-explorer-'));
const site = path.join(work, 'site');
const shots = process.env.SHADELAB_EXPLORER_SCREENSHOTS;
let browser;
let page;
const consoleErrors = [];

function cli(args) { return execFileSync(exe, args, { encoding: 'utf8', maxBuffer: 64 << 20 }); }
function cliJson(args) { return JSON.parse(cli(args)); }

async function open(query) {
  // A fresh document each time: ready counts the page's updates from 1.
  await page.goto(pathToFileURL(path.join(site, 'index.html')).href + query);
  await page.waitForFunction(() => document.body.dataset.ready ||
                                   document.getElementById('shadelab-status').textContent === 'failed', null, { timeout: 60000 });
  return JSON.parse(await page.locator('#shadelab-state').textContent());
}

function relClose(actual, expected, what) {
  for (let i = 0; i < expected.length; ++i) {
    const e = expected[i], a = actual[i];
    const rel = Math.abs(a - e) / Math.max(Math.abs(e), 1e-300);
    assert.ok(a === e || rel <= 1e-12, `${what}[${i}]: page ${a}, CLI ${e} (relative ${rel})`);
  }
}

before(async () => {
  cli(['explore', '--out', site]);
  browser = await chromium.launch({
    executablePath: process.env.CHROMIUM || '/usr/bin/chromium',
    args: ['--no-sandbox', '--use-angle=swiftshader', '--enable-unsafe-swiftshader', '--disable-quic', '--no-first-run',
           '--disable-background-networking', '--disable-component-update', '--disable-sync', '--disable-extensions',
           '--allow-file-access-from-files'],
  });
  page = await browser.newPage({ viewport: { width: 1400, height: 900 } });
  // The test's own helper in every page: bytes to base64 (see shownPixels below).
  await page.addInitScript(() => {
    window.shadelabBase64 = (bytes) => {
      let s = '';
      for (let i = 0; i < bytes.length; i += 0x8000) s += String.fromCharCode.apply(null, bytes.subarray(i, i + 0x8000));
      return btoa(s);
    };
  });
  page.on('console', (m) => { if (m.type() === 'error') consoleErrors.push(m.text()); });
  page.on('pageerror', (e) => consoleErrors.push(String(e)));
});

after(async () => {
  if (browser) await browser.close();
  fs.rmSync(work, { recursive: true, force: true });
});

const CASES = [
  { model: 'phong', params: { kd: '0', ks: '1', n: '100' }, theta: '0,45', wi: '0.3,0.1,0.9', wo: '-0.4,0,0.8' },
  { model: 'blinn-phong-modified', params: { n: '300', kd: '0.1,0.35,0.12', ks: '0.2' }, theta: '0,30,60,85', wi: '0,0,1', wo: '0.5,0.5,0.7' },
  { model: 'cook-torrance', params: { kd: '0', ks: '1', d: 'beckmann', g: 'smith', f: 'schlick', f0: '1,0.78,0.34', m: '0.15' },
    theta: '10,70', wi: '0.2,0,1', wo: '-0.3,0.05,1' },
  { model: 'ward-anisotropic', params: { kd: '0.05', ks: '0.6', alpha_x: '0.3', alpha_y: '0.05' }, theta: '0,50,89',
    wi: '0.1,0.4,0.9', wo: '0.2,-0.3,0.9' },
  { model: 'wrapped-diffuse', params: { kd: '0.7,0.5,0.3', w: '0.5' }, theta: '0,75', wi: '0.9,0,0.1', wo: '0,0,1' },
];

// Rec. 709 luminance of linear RGB (ITU-R BT.709 weights), for the 3D lobe's figures.
const luminance709 = ([r, g, b]) => 0.2126 * r + 0.7152 * g + 0.0722 * b;

// The 3D lobe in the DOM: its grid's shape, wi at the incidence angle in the x-z plane, and a few grid points
// (the normal, the mirror direction, off-plane points, the horizon) equal the luminance of `brdf eval --json`
// at wo = (sin t cos p, sin t sin p, cos t), t = 90 i / (n_theta - 1) degrees, p = 360 j / n_phi degrees.
function checkLobe3d(s, params, what) {
  const l = s.lobe3d;
  assert.equal(l.theta_in, s.lobe.theta_in, what);
  assert.equal(l.luminance.length, l.n_theta, what);
  for (const row of l.luminance) assert.equal(row.length, l.n_phi, what);
  assert.ok(Math.abs(Math.acos(l.wi[2]) - l.theta_in * Math.PI / 180) < 1e-12 && l.wi[1] === 0 && l.wi[0] <= 0, `${what}: wi ${l.wi}`);
  const mirror = Math.round(l.theta_in / (90 / (l.n_theta - 1)));
  const p = Object.entries(params).flatMap(([k, v]) => ['-p', `${k}=${v}`]);
  let positive = 0;
  for (const [i, j] of [[0, 0], [mirror, 0], [mirror, 3], [9, 9], [12, 30], [l.n_theta - 1, 27]]) {
    const t = (90 * i / (l.n_theta - 1)) * Math.PI / 180, ph = 2 * Math.PI * j / l.n_phi;
    const wo = [Math.sin(t) * Math.cos(ph), Math.sin(t) * Math.sin(ph), Math.cos(t)];
    const ev = cliJson(['brdf', 'eval', s.model, ...p, '--wi', l.wi.join(','), '--wo', wo.join(','), '--json']);
    relClose([l.luminance[i][j]], [luminance709(ev.f)], `${what} lobe3d[${i}][${j}]`);
    if (l.luminance[i][j] > 0) ++positive;
  }
  assert.ok(positive >= 2, `${what}: lobe3d is ~0 at the points checked`);
}

function query(c) {
  const q = new URLSearchParams({ model: c.model, ...c.params, theta: c.theta, wi: c.wi, wo: c.wo });
  return '?' + q.toString().replace(/%2C/g, ',');
}

test('albedo and probed f_r in the DOM equal the CLI to 1e-12', async () => {
  for (const c of CASES) {
    const s = await open(query(c));
    assert.deepEqual(s.errors, [], `${c.model}: ${s.errors}`);
    assert.equal(s.model, c.model);
    for (const [k, v] of Object.entries(c.params)) assert.equal(s.params[k], v);
    const p = Object.entries(c.params).flatMap(([k, v]) => ['-p', `${k}=${v}`]);
    const albedo = cliJson(['brdf', 'albedo', c.model, ...p, '--json', '--theta', ...c.theta.split(',')]);
    assert.deepEqual(s.theta, albedo.theta);
    assert.equal(s.albedo.length, albedo.albedo.length);
    albedo.albedo.forEach((a, i) => relClose(s.albedo[i], a, `${c.model} albedo at ${albedo.theta[i]}`));
    const ev = cliJson(['brdf', 'eval', c.model, ...p, '--wi', c.wi, '--wo', c.wo, '--json']);
    relClose(s.probe.f, ev.f, `${c.model} f`);
    assert.deepEqual(s.probe.wi, c.wi.split(',').map(Number));
    checkLobe3d(s, c.params, c.model);
  }
  // The zoo table at the model's exponent is the CLI's.
  const s = await open(query(CASES[0]));
  const zoo = cliJson(['zoo', '--n', '100', '--json']);
  assert.equal(s.zoo.rows.length, zoo.rows.length);
  zoo.rows.forEach((r, i) => relClose([s.zoo.rows[i].numeric, s.zoo.rows[i].closed_form_value], [r.numeric, r.closed_form_value], `zoo ${r.model}`));
});

// Several models at once: the overlaid models' albedo curves are the CLI's, their lobes the library's (the
// same numbers as the model opened on its own), and the button adds the current model to the URL.
test('several models overlaid: their albedo and lobe are the library\'s', async () => {
  const s = await open('?model=phong&n=100&kd=0&ks=1&overlay=lambert:kd=0.5;cook-torrance:m=0.2:f0=1,0.78,0.34');
  assert.deepEqual(s.errors, []);
  assert.equal(new URL(page.url()).searchParams.get('overlay'), 'lambert:kd=0.5;cook-torrance:m=0.2:f0=1,0.78,0.34');
  assert.deepEqual(s.overlays.map((o) => o.model), ['lambert', 'cook-torrance']);
  for (const o of s.overlays) {
    const p = Object.entries(o.params).flatMap(([k, v]) => ['-p', `${k}=${v}`]);
    const albedo = cliJson(['brdf', 'albedo', o.model, ...p, '--json', '--theta', ...o.albedo_curve.theta.map(String)]);
    albedo.albedo.forEach((a, i) => relClose(o.albedo_curve.albedo[i], a, `overlay ${o.model} albedo at ${albedo.theta[i]}`));
  }
  const alone = await open('?model=cook-torrance&m=0.2&f0=1,0.78,0.34');
  assert.deepEqual(alone.lobe.luminance, s.overlays[1].lobe.luminance);
  const before = await page.evaluate(() => document.body.dataset.ready);
  await page.click('#shadelab-overlay-add');
  await page.waitForFunction((b) => document.body.dataset.ready !== b, before);
  const added = JSON.parse(await page.locator('#shadelab-state').textContent());
  assert.equal(added.view.overlay, 'cook-torrance:m=0.2:f0=1,0.78,0.34');
  assert.deepEqual(added.overlays[0].albedo_curve, alone.albedo_curve);
  if (shots) {
    await open('?model=phong&n=100&kd=0&ks=1&scale=log&overlay=blinn-phong-modified:n=400:kd=0;cook-torrance:kd=0:m=0.2');
    await page.locator('#views').screenshot({ path: path.join(shots, 'explorer-overlay.png') });
  }
});

test('the exported shader of the export button is the CLI export', async () => {
  await open(query(CASES[0]));
  await page.selectOption('#shadelab-export-lang', 'hlsl');
  const [download] = await Promise.all([page.waitForEvent('download'), page.click('#shadelab-export')]);
  const text = fs.readFileSync(await download.path(), 'utf8');
  // The page passes the parameters in the registry's order (kd, ks, n), as CASES[0] lists them.
  const p = Object.entries(CASES[0].params).flatMap(([k, v]) => ['--param', `${k}=${v}`]);
  assert.equal(text, cli(['shader', 'phong', ...p, '--lang', 'hlsl']));
});

test('the URL state round-trips', async () => {
  const first = await open(query(CASES[1]) + '&units=radiometric&light=3&exposure=-1&scale=log&cos=1&theta_in=30');
  assert.deepEqual(first.errors, []);
  // The page rewrote the URL into its canonical query; loading that reproduces the same state.
  assert.equal(new URL(page.url()).search, first.query);
  const again = await open(first.query);
  for (const s of [first, again]) delete s.update_ms;
  assert.deepEqual(again, first);
  assert.equal(first.view.units, 'radiometric');
  assert.equal(first.lobe.theta_in, 30);
  checkLobe3d(first, CASES[1].params, 'theta_in=30');
  // A changed control changes the URL, and the new URL reproduces it.
  const before = await page.evaluate(() => document.body.dataset.ready);
  await page.fill('#shadelab-param-n', '40');
  await page.dispatchEvent('#shadelab-param-n', 'change');
  await page.waitForFunction((b) => document.body.dataset.ready !== b, before);
  const changed = JSON.parse(await page.locator('#shadelab-state').textContent());
  assert.equal(changed.params.n, '40');
  assert.match(page.url(), /[?&]n=40(&|$)/);
  const reloaded = await open(new URL(page.url()).search);
  assert.equal(reloaded.params.n, '40');
  relClose(reloaded.albedo.flat(), changed.albedo.flat(), 'albedo after reload');
});

test('a bad URL parameter shows a message naming it and the page still draws', async () => {
  for (const [q, name] of [['?model=phong&n=-1', "'n'"], ['?model=no-such-model', "'model'"], ['?model=phong&colour=1', "'colour'"],
                           ['?model=phong&theta=0,95', "'theta'"], ['?model=phong&wi=1,2', "'wi'"], ['?model=lambert&kd=abc', "'kd'"],
                           ['?model=phong&lighting=sun', "'lighting'"], ['?model=phong&lighting=hdri&env=nosuch', "'env'"],
                           ['?model=phong&overlay=nosuch', "'overlay'"], ['?model=phong&overlay=lambert:kd=-1', "'overlay'"]]) {
    const s = await open(q);
    const box = page.locator('#shadelab-error');
    assert.ok(await box.isVisible(), q);
    assert.ok((await box.textContent()).includes(name), `${q}: ${await box.textContent()}`);
    assert.ok(s.albedo.length > 0 && s.probe.f.length === 3, `${q}: no figures`);
  }
  const ok = await open('?model=phong');
  assert.deepEqual(ok.errors, []);
  assert.ok(!(await page.locator('#shadelab-error').isVisible()));
});

// The scene `shadelab render --mode game` renders for the page's sphere state.
function sceneFor(s) {
  const value = (v) => {
    const parts = String(v).split(',');
    if (parts.every((x) => x.trim() !== '' && Number.isFinite(Number(x)))) return parts.length === 1 ? Number(v) : parts.map(Number);
    return v;
  };
  const params = Object.fromEntries(Object.entries(s.params).map(([k, v]) => [k, value(v)]));
  const sp = s.sphere;
  const colour = sp.light.length === 1 ? [sp.light[0], sp.light[0], sp.light[0]] : sp.light;
  const scene = {
    units: sp.units,
    camera: { position: sp.camera.position, look_at: sp.camera.look_at, up: sp.camera.up, fov: sp.camera.fov, width: sp.width, height: sp.height },
    materials: { m: { model: s.model, params } },
    shapes: [{ type: 'sphere', center: sp.center, radius: sp.radius, material: 'm' }],
    lights: sp.lighting === 'hdri' ? [] : [{ type: 'point', position: sp.light_position, color: colour, intensity: 1 }],
  };
  if (sp.lighting !== 'point') scene.environment = { file: sp.env_file };
  return scene;
}

// The pixels all of whose sub-pixel rays hit the sphere (the renderer's camera rays; render/game_renderer.cpp).
function spherePixels(sp) {
  const sub = (a, b) => a.map((x, i) => x - b[i]);
  const unit = (a) => { const l = Math.hypot(...a); return a.map((x) => x / l); };
  const cross = (a, b) => [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]];
  const cam = sp.camera, w = sp.width, h = sp.height, side = Math.round(Math.sqrt(sp.spp));
  const forward = unit(sub(cam.look_at, cam.position)), right = unit(cross(forward, cam.up)), up = cross(right, forward);
  const tanHalf = Math.tan(0.5 * cam.fov * Math.PI / 180);
  const eye = sub(cam.position, sp.center);
  const inside = [];
  for (let y = 0; y < h; ++y) {
    for (let x = 0; x < w; ++x) {
      let all = true;
      for (let j = 0; j < side && all; ++j) {
        for (let i = 0; i < side && all; ++i) {
          const sx = (2 * (x + (i + 0.5) / side) / w - 1) * tanHalf * (w / h), sy = (1 - 2 * (y + (j + 0.5) / side) / h) * tanHalf;
          const d = unit(forward.map((f, k) => f + right[k] * sx + up[k] * sy));
          const b = eye.reduce((acc, e, k) => acc + e * d[k], 0), c = eye.reduce((acc, e) => acc + e * e, 0) - sp.radius * sp.radius;
          all = b * b - c > 0 && -b - Math.sqrt(b * b - c) > 0;
        }
      }
      if (all) inside.push(y * w + x);
    }
  }
  return inside;
}

// Renders the page's sphere state with `shadelab render --mode game` and returns its 8-bit pixels.
async function renderReference(s, name) {
  const scene = path.join(work, `${name}.json`);
  fs.writeFileSync(scene, JSON.stringify(sceneFor(s)));
  const exr = path.join(work, `${name}.exr`), png = path.join(work, `${name}.png`);
  // The renderer's defaults: ggx and filament under an HDRI with the split sum (lookup lobes), which the page
  // shades with the exported text (`shader MODEL --ibl`).
  const args = ['render', scene, '--mode', 'game', '--spp', String(s.sphere.spp), '--out', exr, '--png', png,
                '--exposure', String(s.sphere.exposure)];
  if (s.sphere.tone === 'filmic') args.push('--filmic');
  else if (s.sphere.tone !== 'clamp') args.push('--view', s.sphere.tone);  // the other views of kernels/display.sl
  if (s.sphere.lighting !== 'point') args.push('--env-size', String(s.sphere.env_size), '--specular-size', String(s.sphere.specular_size));
  cli(args);
  return pngPixels(png);
}

async function pngPixels(file) {
  const data = fs.readFileSync(file).toString('base64');
  const b64 = page.evaluate(async (b64) => {
    const img = new Image();
    img.src = 'data:image/png;base64,' + b64;
    await img.decode();
    const c = document.createElement('canvas');
    c.width = img.width; c.height = img.height;
    const ctx = c.getContext('2d');
    ctx.drawImage(img, 0, 0);
    return window.shadelabBase64(ctx.getImageData(0, 0, img.width, img.height).data);
  }, data);
  return Buffer.from(await b64, 'base64');
}

// Large pixel arrays cross from the page as base64 text: Playwright serializes a JavaScript array element by
// element, which took 2-4 s per 384 x 384 image (4 of the 12 s of a view).
async function shownPixels() {
  const r = await page.evaluate(() => {
    const p = window.shadelabSpherePixels();
    return { width: p.width, height: p.height, b64: window.shadelabBase64(Uint8Array.from(p.rgba)) };
  });
  return { width: r.width, height: r.height, rgba: Buffer.from(r.b64, 'base64') };
}

test('the WebGL 2 sphere matches the C++ game renderer within 1/255 mean absolute difference', async () => {
  const views = [
    '?model=blinn-phong-modified&n=300&kd=0.1,0.35,0.12&ks=0.2&units=game&light=2&light_pos=2,2,3',
    '?model=cook-torrance&kd=0.05&ks=1&d=beckmann&g=smith&f=schlick&f0=1,0.78,0.34&m=0.25&units=radiometric&light=20&light_pos=-2,3,4&exposure=-1',
    '?model=lambert&kd=0.8&units=game&light=1&light_pos=0,0,5&tone=filmic&exposure=1',
    '?model=ggx&units=game&light=2&light_pos=2,2,3',
    '?model=lambert&kd=0.8,0.3,0.1&units=game&light=3&light_pos=0,0,5&tone=agx&exposure=1',
    '?model=ggx&units=game&light=6&light_pos=2,2,3&tone=pbr-neutral',
  ];
  for (const [i, q] of views.entries()) {
    const s = await open(q);
    assert.deepEqual(s.errors, [], q);
    const shown = await shownPixels();
    const ref = await renderReference(s, `sphere${i}`);
    assert.equal(ref.length, shown.rgba.length);
    let sum = 0, lit = 0, max = 0;
    for (let k = 0; k < ref.length; ++k) {
      if (k % 4 === 3) continue;
      const d = Math.abs(ref[k] - shown.rgba[k]);
      sum += d; max = Math.max(max, d);
      if (shown.rgba[k] > 0) ++lit;
    }
    const mean = sum / (ref.length * 3 / 4);
    console.log(`sphere ${s.model} (${s.sphere.units}): mean |difference| ${mean.toFixed(4)} / 255, max ${max}, lit channels ${lit}`);
    assert.ok(lit > ref.length / 10, `${q}: the sphere is black`);
    assert.ok(mean <= 1.0, `${q}: mean absolute difference ${mean} / 255`);
  }
});

// The HDRI sphere: SH9 diffuse and prefiltered specular of a blender-data map baked by `shadelab explore` with
// the renderer's own bake, shaded by the page's GLSL (the kernels of game_ambient.sl and sh9.sl, the cube lookup,
// the level choice; for ggx and filament the split sum of `shader MODEL --ibl`, kernels/game_ibl.sl, read
// seamlessly), against `render --mode game` of the same scene at the same bake sizes (its defaults: the split
// sum, lookup lobes). Compared over the sphere's pixels: behind it the page shows the baked 32^2 radiance cube,
// the renderer the full map.
const HDRI_VIEWS = [
  '?model=blinn-phong-modified&n=300&kd=0.1,0.35,0.12&ks=0.2&lighting=hdri&env=forest',
  '?model=cook-torrance&kd=0.05&ks=1&d=beckmann&g=smith&f=schlick&f0=1,0.78,0.34&m=0.25&lighting=both&env=studio&light=2&exposure=-0.5',
  '?model=phong&kd=0.2&ks=0.8&n=1000&lighting=hdri&env=city&exposure=1',
  '?model=wrapped-diffuse&kd=0.7,0.5,0.3&w=0.5&lighting=hdri&env=sunset&tone=filmic&exposure=1',
  '?model=ggx&lighting=hdri&env=courtyard',
  '?model=ggx&roughness=0.25&f0=0.9,0.6,0.3&kd=0&lighting=hdri&env=studio&exposure=-0.5',
  '?model=filament&base_color=0.8,0.2,0.1&perceptual_roughness=0.35&lighting=both&env=courtyard&light=2',
  '?model=filament&metallic=1&base_color=0.95,0.64,0.54&perceptual_roughness=0.2&lighting=hdri&env=studio&tone=filmic',
];

test('the HDRI-lit sphere matches the C++ game renderer within 1/255 mean absolute difference', async (t) => {
  const first = await open('?model=phong');
  if (first.sphere.environments.length === 0) { t.skip(`no HDRI on this machine: ${first.sphere.env_message}`); return; }
  assert.equal(first.sphere.environments.length, 8, first.sphere.environments.join(','));
  for (const [i, q] of HDRI_VIEWS.entries()) {
    const s = await open(q);
    assert.deepEqual(s.errors, [], q);
    assert.equal(s.sphere.env, new URLSearchParams(q).get('env'));
    assert.ok(s.sphere.env_file.endsWith(`${s.sphere.env}.exr`), s.sphere.env_file);
    const shown = await shownPixels();
    const ref = await renderReference(s, `hdri${i}`);
    assert.equal(ref.length, shown.rgba.length);
    const inside = spherePixels(s.sphere);
    let sum = 0, max = 0, lit = 0;
    for (const p of inside) {
      for (let k = 0; k < 3; ++k) {
        const d = Math.abs(ref[4 * p + k] - shown.rgba[4 * p + k]);
        sum += d; max = Math.max(max, d);
        if (shown.rgba[4 * p + k] > 0) ++lit;
      }
    }
    const mean = sum / (inside.length * 3);
    console.log(`hdri ${s.model} (${s.sphere.lighting}, ${s.sphere.env}): mean |difference| ${mean.toFixed(4)} / 255 over ${inside.length} sphere pixels, max ${max}`);
    assert.ok(inside.length > 3000, `${inside.length} sphere pixels`);
    assert.ok(lit > inside.length * 2, `${q}: the sphere is black`);
    assert.ok(mean <= 1.0, `${q}: mean absolute difference ${mean} / 255`);
    if (shots && i === 1) await page.locator('#shadelab-sphere').screenshot({ path: path.join(shots, 'explorer-hdri.png') });
  }
});

test('without blender-data the page says so and keeps the point light', async () => {
  const empty = path.join(work, 'no-hdri');
  fs.mkdirSync(empty);
  const other = path.join(work, 'site-no-hdri');
  cli(['explore', '--out', other, '--env-dir', empty]);
  await page.goto(pathToFileURL(path.join(other, 'index.html')).href + '?model=phong&lighting=hdri');
  await page.waitForFunction(() => document.body.dataset.ready, null, { timeout: 60000 });
  const s = JSON.parse(await page.locator('#shadelab-state').textContent());
  assert.deepEqual(s.sphere.environments, []);
  assert.match(s.sphere.env_message, /no HDRI/);
  assert.equal(s.sphere.lighting, 'point');
  assert.ok((await page.locator('#shadelab-error').textContent()).includes("'lighting'"));
  assert.match(await page.locator('#shadelab-env-status').textContent(), /no HDRI/);
  const shown = await shownPixels();
  assert.ok(shown.rgba.some((v, k) => k % 4 !== 3 && v > 0), 'the point-lit sphere is drawn');
});

test('no console error on any page load', async () => {
  if (shots) {
    fs.mkdirSync(shots, { recursive: true });
    await open('?model=cook-torrance&kd=0.05&ks=1&d=beckmann&g=smith&f=schlick&f0=1,0.78,0.34&m=0.25&units=game&light=2&light_pos=2,2,3&scale=log&lighting=both&env=studio');
    await page.screenshot({ path: path.join(shots, 'explorer.png'), fullPage: true });
    await open('?model=phong&n=-1');
    await page.locator('#shadelab-error').screenshot({ path: path.join(shots, 'explorer-error.png') });
  }
  assert.deepEqual(consoleErrors, []);
});
