// The pieces of shadelab's comparison pages (report_page.h).
#include "report_page.h"

#include <fmt/core.h>

#include <algorithm>
#include <cmath>

#include "shadelab/core/text.h"
#include "shadelab/image/metrics.h"
#include "shadelab/image/srgb.h"

namespace shadelab::cli {

const char* report_page_css() {
  return R"CSS(
body{font-family:system-ui,sans-serif;margin:0 auto;max-width:1500px;padding:1em 2em;color:#222;background:#fafafa}
h1{font-size:1.5em}h2{margin-top:2em;border-bottom:1px solid #ccc}
table{border-collapse:collapse;margin:.5em 0}td,th{border:1px solid #ccc;padding:2px 8px;text-align:right}
th{background:#eee}td:first-child,th:first-child{text-align:left}
tr.material{cursor:pointer}tr.material:hover{background:#eef}tr.material.selected{background:#fd8;outline:2px solid #c80}
.viewer{margin:.5em 0}.controls{display:flex;flex-wrap:wrap;gap:.4em 1em;align-items:center;margin:.3em 0}
.controls button{padding:2px 10px}.controls button.on{background:#333;color:#fff}
.view{position:relative;overflow:hidden;background:#444;border:1px solid #888;max-width:100%;cursor:grab;touch-action:none}
.view.dragging{cursor:grabbing}
.stage{position:absolute;left:0;top:0;transform-origin:0 0}
.stage img,.stage canvas{position:absolute;left:0;top:0;image-rendering:pixelated;user-select:none;-webkit-user-drag:none}
.stage .divider{position:absolute;top:0;width:0;border-left:1px solid #fff;box-shadow:0 0 2px #000;pointer-events:none}
.label{position:absolute;top:4px;padding:1px 6px;background:rgba(0,0,0,.6);color:#fff;font-size:12px;pointer-events:none}
.bar{margin:.3em 0;max-width:520px}.bar .ramp{height:14px;border:1px solid #888}
.bar .ticks{position:relative;height:1.2em;font-size:12px}.bar .ticks span{position:absolute;transform:translateX(-50%)}
.bar .ticks span:first-child{transform:none}.bar .ticks span:last-child{transform:translateX(-100%)}
.bar .caption{font-size:12px;color:#555}
.figures td{font-variant-numeric:tabular-nums}
.maps{display:flex;flex-wrap:wrap;gap:1em}.maps figure{margin:0;flex:0 1 480px}
.maps img{image-rendering:pixelated;width:100%}
)CSS";
}

std::string exact_number(double v) { return std::isfinite(v) ? fmt::format("{}", v) : std::string("null"); }

std::string colour_bar_html(double scale, const std::string& caption, const std::string& json_pointer) {
  std::string stops;
  constexpr int n = 16;
  for (int i = 0; i <= n; ++i) {
    const Rgb c = heat_ramp(static_cast<double>(i) / n);
    stops += fmt::format("{}#{:02x}{:02x}{:02x} {}%", i == 0 ? "" : ",", linear_to_srgb8(c.r), linear_to_srgb8(c.g),
                         linear_to_srgb8(c.b), 100 * i / n);
  }
  std::string ticks;
  for (int i = 0; i <= 4; ++i) {
    ticks += fmt::format("<span style=\"left:{}%\">{:.3g}</span>", 25 * i, scale * i / 4.0);
  }
  const std::string attr = json_pointer.empty() ? std::string() : " data-json=\"" + xml_escape(json_pointer) + "\"";
  return fmt::format("<div class=\"bar\" data-scale=\"{}\"{}><div class=\"ramp\" style=\"background:linear-gradient(to right,{})\">"
                     "</div><div class=\"ticks\">{}</div><div class=\"caption\">{}</div></div>",
                     exact_number(scale), attr, stops, ticks, xml_escape(caption));
}

std::string viewer_html(const std::string& id, int width, int height, const std::vector<ViewerLayer>& layers,
                        const std::string& heat_bar, const std::string& flip_bar) {
  std::string modes, imgs;
  bool heat = false, flip = false;
  for (const ViewerLayer& l : layers) {
    imgs += fmt::format("<img class=\"layer {0}\" data-layer=\"{0}\" src=\"{1}\" width=\"{2}\" height=\"{3}\" alt=\"{4}\" draggable=\"false\">",
                        xml_escape(l.name), xml_escape(l.src), width, height, xml_escape(l.caption));
    heat = heat || l.name == "heat";
    flip = flip || l.name == "flip";
  }
  modes += "<button data-mode=\"swipe\" class=\"on\">swipe</button><button data-mode=\"flip\">flip</button>";
  if (heat) modes += "<button data-mode=\"heat\">error heat map</button>";
  if (flip) modes += "<button data-mode=\"flipmap\">FLIP map</button>";
  // Small images open magnified by a whole number (square pixels) to about 640 pixels wide.
  const int start = width < 640 ? std::max(1, 640 / std::max(width, 1)) : 1;
  return fmt::format(
      "<div class=\"viewer\" id=\"{0}\" data-width=\"{1}\" data-height=\"{2}\" data-start-zoom=\"{7}\">\n<div class=\"controls\"><span>{3}</span>"
      "<label>swipe <input type=\"range\" class=\"swipe\" min=\"0\" max=\"100\" value=\"50\"></label>"
      "<button class=\"toggle\" title=\"key F\">show reference</button>"
      "<label>zoom <select class=\"zoom\"><option value=\"fit\">fit</option><option value=\"1\">1:1</option>"
      "<option value=\"2\">2x</option><option value=\"4\">4x</option><option value=\"8\">8x</option><option value=\"16\">16x</option>"
      "</select></label><span class=\"hint\">drag to pan, wheel to zoom</span></div>\n"
      "<div class=\"view\" style=\"width:{8}px;height:{9}px\"><div class=\"stage\" style=\"width:{1}px;height:{2}px\">{4}"
      "<canvas class=\"mask\" width=\"{1}\" height=\"{2}\" data-highlighted=\"0\"></canvas><div class=\"divider\" style=\"height:{2}px\"></div></div>"
      "<span class=\"label left\" style=\"left:4px\">game</span><span class=\"label right\" style=\"right:4px\">reference</span></div>\n"
      "<div class=\"heatbar\" hidden>{5}</div><div class=\"flipbar\" hidden>{6}</div>\n</div>\n",
      xml_escape(id), width, height, modes, imgs, heat_bar, flip_bar, start, width * start, height * start);
}

const char* report_page_script() {
  return R"JS(
(function () {
  'use strict';
  const dataNode = document.getElementById('report-data');
  const data = dataNode ? JSON.parse(dataNode.textContent) : {};
  function decode(rle, n) {
    const ids = new Int32Array(n).fill(-1);
    let p = 0;
    for (let i = 0; i + 1 < rle.length; i += 2) { ids.fill(rle[i], p, p + rle[i + 1]); p += rle[i + 1]; }
    return ids;
  }
  const ids = data.material_ids ? decode(data.material_ids, data.width * data.height) : null;

  function setupViewer(v) {
    const w = Number(v.dataset.width), h = Number(v.dataset.height);
    const view = v.querySelector('.view'), stage = v.querySelector('.stage');
    const layer = (name) => v.querySelector('img[data-layer="' + name + '"]');
    const game = layer('game'), ref = layer('reference'), heat = layer('heat'), flipMap = layer('flip');
    const divider = v.querySelector('.divider'), mask = v.querySelector('canvas.mask');
    const swipe = v.querySelector('input.swipe'), toggle = v.querySelector('button.toggle');
    const zoomSel = v.querySelector('select.zoom');
    const left = v.querySelector('.label.left'), right = v.querySelector('.label.right');
    const heatBar = v.querySelector('.heatbar'), flipBar = v.querySelector('.flipbar');
    const st = { mode: 'swipe', showGame: true, zoom: Number(v.dataset.startZoom) || 1, x: 0, y: 0, swipe: 50 };

    function clampPan() {
      const vw = view.clientWidth, vh = view.clientHeight;
      const sw = w * st.zoom, sh = h * st.zoom;
      st.x = sw <= vw ? (vw - sw) / 2 : Math.min(0, Math.max(vw - sw, st.x));
      st.y = sh <= vh ? (vh - sh) / 2 : Math.min(0, Math.max(vh - sh, st.y));
    }
    function apply() {
      clampPan();
      stage.style.transform = 'translate(' + st.x + 'px,' + st.y + 'px) scale(' + st.zoom + ')';
      const show = (el, on) => { if (el) el.style.visibility = on ? 'visible' : 'hidden'; };
      show(ref, st.mode === 'swipe' || (st.mode === 'flip' && !st.showGame));
      show(game, st.mode === 'swipe' || (st.mode === 'flip' && st.showGame));
      show(heat, st.mode === 'heat');
      show(flipMap, st.mode === 'flipmap');
      game.style.clipPath = st.mode === 'swipe' ? 'inset(0 ' + (100 - st.swipe) + '% 0 0)' : 'none';
      divider.style.display = st.mode === 'swipe' ? '' : 'none';
      divider.style.left = (w * st.swipe / 100) + 'px';
      divider.style.borderLeftWidth = (1 / st.zoom) + 'px';
      left.textContent = st.mode === 'swipe' ? 'game' : st.mode === 'flip' ? (st.showGame ? 'game' : 'reference') :
                         st.mode === 'heat' ? 'relative error' : 'FLIP';
      right.style.display = st.mode === 'swipe' ? '' : 'none';
      toggle.textContent = st.showGame ? 'show reference' : 'show game';
      toggle.disabled = st.mode !== 'flip';
      swipe.disabled = st.mode !== 'swipe';
      heatBar.hidden = st.mode !== 'heat';
      flipBar.hidden = st.mode !== 'flipmap';
      for (const b of v.querySelectorAll('button[data-mode]')) b.classList.toggle('on', b.dataset.mode === st.mode);
      v.dataset.mode = st.mode;
      v.dataset.zoom = String(st.zoom);
      v.dataset.shown = st.mode === 'flip' ? (st.showGame ? 'game' : 'reference') : st.mode;
    }
    function zoomTo(z, cx, cy) {
      z = Math.min(64, Math.max(1 / 16, z));
      if (cx === undefined) { cx = view.clientWidth / 2; cy = view.clientHeight / 2; }
      const ix = (cx - st.x) / st.zoom, iy = (cy - st.y) / st.zoom;  // image point kept under (cx, cy)
      st.zoom = z;
      st.x = cx - ix * z;
      st.y = cy - iy * z;
      let opt = Array.from(zoomSel.options).find((o) => o.value !== 'fit' && Number(o.value) === z);
      if (!opt) {  // a magnification the list lacks (wheel, fit, the start): one extra entry names it
        opt = zoomSel.querySelector('option.other') || zoomSel.appendChild(document.createElement('option'));
        opt.className = 'other';
        opt.value = String(z);
        opt.textContent = (z >= 1 ? z : z.toFixed(2)) + 'x';
      }
      zoomSel.value = opt.value;
      apply();
    }
    function fit() {  // the largest whole magnification that shows the whole image, or the reduction that does
      const f = Math.min(view.clientWidth / w, view.clientHeight / h);
      return f >= 1 ? Math.floor(f) : f;
    }
    for (const b of v.querySelectorAll('button[data-mode]')) {
      b.addEventListener('click', () => { st.mode = b.dataset.mode; apply(); });
    }
    swipe.addEventListener('input', () => { st.swipe = Number(swipe.value); apply(); });
    toggle.addEventListener('click', () => { st.showGame = !st.showGame; apply(); });
    zoomSel.addEventListener('change', () => zoomTo(zoomSel.value === 'fit' ? fit() : Number(zoomSel.value)));
    view.addEventListener('wheel', (e) => {
      e.preventDefault();
      const r = view.getBoundingClientRect();
      zoomTo(st.zoom * (e.deltaY < 0 ? 2 : 0.5), e.clientX - r.left, e.clientY - r.top);
    }, { passive: false });
    let drag = null;
    view.addEventListener('pointerdown', (e) => {
      drag = { px: e.clientX, py: e.clientY, x: st.x, y: st.y };
      view.classList.add('dragging');
      view.setPointerCapture(e.pointerId);
    });
    view.addEventListener('pointermove', (e) => {
      if (!drag) return;
      st.x = drag.x + e.clientX - drag.px;
      st.y = drag.y + e.clientY - drag.py;
      apply();
    });
    const end = () => { drag = null; view.classList.remove('dragging'); };
    view.addEventListener('pointerup', end);
    view.addEventListener('pointercancel', end);
    v.addEventListener('keydown', (e) => { if (e.key === 'f' || e.key === 'F') { st.mode = 'flip'; st.showGame = !st.showGame; apply(); } });
    v.tabIndex = 0;

    // A material's pixels, drawn over the images in a bright colour; the rest is dimmed.
    v.highlight = (material) => {
      const ctx = mask.getContext('2d');
      ctx.clearRect(0, 0, w, h);
      let count = 0;
      if (material !== null && ids) {
        const img = ctx.createImageData(w, h);
        for (let i = 0; i < w * h; ++i) {
          const hit = ids[i] === material;
          img.data[4 * i] = hit ? 255 : 0;
          img.data[4 * i + 1] = hit ? 40 : 0;
          img.data[4 * i + 2] = hit ? 200 : 0;
          img.data[4 * i + 3] = hit ? 110 : 150;
          if (hit) ++count;
        }
        ctx.putImageData(img, 0, 0);
      }
      mask.dataset.highlighted = String(count);
      mask.dataset.material = material === null ? '' : String(material);
    };
    zoomTo(st.zoom);
  }

  document.querySelectorAll('.viewer').forEach(setupViewer);
  document.querySelectorAll('tr.material').forEach((row) => {
    row.addEventListener('click', () => {
      const v = document.getElementById(row.closest('[data-viewer]').dataset.viewer);
      const selected = !row.classList.contains('selected');
      row.closest('table').querySelectorAll('tr.material').forEach((r) => r.classList.remove('selected'));
      row.classList.toggle('selected', selected);
      v.highlight(selected ? Number(row.dataset.material) : null);
    });
  });
  document.body.dataset.ready = '1';
})();
)JS";
}

std::vector<int> run_lengths(const std::vector<int>& ids) {
  std::vector<int> out;
  for (std::size_t i = 0; i < ids.size();) {
    std::size_t j = i;
    while (j < ids.size() && ids[j] == ids[i]) ++j;
    out.push_back(ids[i]);
    out.push_back(static_cast<int>(j - i));
    i = j;
  }
  return out;
}

}  // namespace shadelab::cli
