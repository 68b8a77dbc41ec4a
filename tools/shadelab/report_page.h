// The pieces of shadelab's comparison pages (`shadelab report`, `shadelab ibl-error`): one self-contained
// HTML file each (inline CSS and script, the images as files beside it; nothing from the network, so they
// open from file:// with no server).
//   - report_page_css(): the pages' style sheet;
//   - colour_bar_html(): the heat ramp (metrics.h heat_ramp) as a bar with its numeric scale;
//   - viewer_html(): a full-size viewer of game against reference: swipe, flip, the error heat map and the
//     FLIP map, zoom (nearest-neighbour pixels) and pan, and a mask layer for a material's pixels;
//   - report_page_script(): the script that drives every viewer and material row of a page.
// docs/cli.md (report) describes the page; tools/explore/test/report.test.mjs tests it in Chromium.
#pragma once

#include <string>
#include <vector>

namespace shadelab::cli {

const char* report_page_css();

// A horizontal bar of the heat ramp from 0 to `scale` with five ticks; `json_pointer` (may be empty) names
// the scale's value in the command's --json output for the page's test.
std::string colour_bar_html(double scale, const std::string& caption, const std::string& json_pointer);

struct ViewerLayer {
  std::string src;      // image file, relative to the page
  std::string name;     // the mode's name: game, reference, heat, flip
  std::string caption;  // what the control says
};

// A viewer for images of width x height; `id` is unique in the page. The layers must include game and
// reference; heat and flip add modes. `bars` are colour_bar_html()s shown with the heat and flip modes, in
// that order (empty strings for none).
std::string viewer_html(const std::string& id, int width, int height, const std::vector<ViewerLayer>& layers,
                        const std::string& heat_bar, const std::string& flip_bar);

const char* report_page_script();

// Run-length code of a material-id image for the page's script: [id, count, id, count, ...].
std::vector<int> run_lengths(const std::vector<int>& ids);

// A number for a data-value attribute: the shortest text that reads back as the same double (what the JSON
// output writes), or "null" for NaN and infinities.
std::string exact_number(double v);

}  // namespace shadelab::cli
