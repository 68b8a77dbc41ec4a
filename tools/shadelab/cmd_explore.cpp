// shadelab explore [--out DIR] [--serve [--port P]]: the browser explorer (docs/explorer.md) written as a
// static site that works from file://, or served on 127.0.0.1.
#include <fmt/core.h>

#include <iostream>

#include "cli_common.h"
#include "site.h"

namespace shadelab::cli {

namespace {

struct ExploreOptions {
  std::string out = "shadelab-explorer";
  bool serve = false;
  int port = 8080;
  explore::SiteOptions site;
};

void run_explore(const ExploreOptions& o, bool port_given) {
  if (port_given && !o.serve) throw UsageError("--port: only with --serve");
  if (o.port < 0 || o.port > 65535) throw UsageError(fmt::format("--port: {} is out of range [0, 65535]", o.port));
  work_begins();
  const auto report = unwrap(explore::write_site(o.out, o.site));
  const std::filesystem::path index = std::filesystem::absolute(o.out) / "index.html";
  fmt::print("wrote {} files to {}\n", report.written.size(), std::filesystem::absolute(o.out).string());
  for (const auto& p : report.env_problems) warn("HDRI skipped: " + p);
  if (report.environments.empty()) {
    warn(report.env_message + "; the sphere has the point light only");
  } else {
    fmt::print("baked {} HDRIs from {} at {} x {} (SH9 and prefiltered specular, {:.2f} s)\n", report.environments.size(),
               o.site.env_dir.string(), o.site.env_size, o.site.env_size, report.bake_seconds);
  }
  if (!o.serve) {
    fmt::print("open file://{}\n", index.string());
    return;
  }
  unwrap(explore::serve_site(o.out, o.port, [](int port) {
    fmt::print("serving on http://127.0.0.1:{}/ (Ctrl-C stops)\n", port);
    std::cout.flush();
    std::fflush(stdout);
  }));
}

void add_explore_command(CLI::App& app, Command& command) {
  auto o = std::make_shared<ExploreOptions>();
  auto* sub = app.add_subcommand("explore", "the BRDF explorer in the browser: write its static site (open index.html), "
                                            "or serve it on 127.0.0.1");
  sub->add_option("--out", o->out, "folder to write the site into")->capture_default_str();
  sub->add_option("--env-dir", o->site.env_dir, "folder of lat-long .exr HDRIs baked for the sphere")->capture_default_str();
  sub->add_option("--env-size", o->site.env_size, "face size the HDRIs are baked at (a power of two, at most 256)")
      ->capture_default_str();
  sub->add_flag("--serve", o->serve, "serve the site on 127.0.0.1 and print the URL");
  sub->add_option("--port", o->port, "port for --serve (0: any free port)")->capture_default_str();
  sub->callback([o, &command, sub] {
    const bool port_given = sub->count("--port") > 0;
    command.run = [o, port_given] { run_explore(*o, port_given); };
  });
}

}  // namespace

const CommandRegistration registration_explore(97, add_explore_command);

}  // namespace shadelab::cli
