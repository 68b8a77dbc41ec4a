// shadelab plot internals: input checks shared by the line and the polar chart (plot.cpp).
//
// Contract: internal to the plot module. Each check returns true or an Error whose one-line message starts
// with the plot's name ("line plot 'Albedo': ...", or "line plot: ..." when the title is empty) and names
// the series or field at fault.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "shadelab/core/error.h"
#include "shadelab/plot/plot.h"

namespace shadelab::plot_detail {

// Well-formed UTF-8: no overlong forms, surrogates or code points beyond U+10FFFF.
bool is_valid_utf8(std::string_view text);

// "line plot 'Albedo'" / "polar plot" (kind is "line plot" or "polar plot").
std::string plot_name(std::string_view kind, const std::string& title);

// width and height in [plot_min_size, plot_max_size].
Result<bool> check_size(const std::string& name, int width, int height);

// `text` is valid UTF-8; `field` names it in the message ("title", "x axis label", ...).
Result<bool> check_text(const std::string& name, std::string_view field, const std::string& text);

// Every series: a label of valid UTF-8, at least one point, as many y as x, no +-Inf, a width in (0, 50],
// a finite colour. NaN is allowed (a gap).
Result<bool> check_series(const std::string& name, const std::vector<Series>& series);

// The shortest text that reads back as `v` ("5", "0.1", "1e-300", "nan"), for messages.
std::string number(double v);

// "series 2 'phong'" or "series 2" (1-based, as a user counts).
std::string series_name(const Series& series, std::size_t index);

}  // namespace shadelab::plot_detail
