// foveal foveate: RMFR in image space on a photograph (forward map with an area
// prefilter to w×h, inverse map back with bilinear filtering).
#include <memory>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "commands.hpp"
#include "foveal/core/atomic_file.hpp"
#include "foveal/image/foveate.hpp"
#include "foveal/runtime/args.hpp"
#include "foveal/runtime/cli.hpp"

namespace foveal::cmd {

namespace {

struct Args {
  std::string in, out, reduced_out, method = "rmfr", fovea = "0.5,0.5";
  double sigma = 2.0, fx = 0.3, fy = 0.3;
  bool json = false;
};

int run(const Args& a) {
  auto fovea = cli::parse_point(a.fovea, "--fovea");
  if (!fovea) return cli::report(fovea.error());
  if (fovea->first < 0 || fovea->first > 1 || fovea->second < 0 || fovea->second > 1)
    return cli::report(bad_input("--fovea: X and Y must lie in [0,1], got '" + a.fovea + "'"));
  for (const std::string* out : {&a.out, &a.reduced_out})
    if (Status s = check_output_is_not_an_input(*out, {a.in}); !s) return cli::report(s.error());
  auto in = image::load(a.in);
  if (!in) return cli::report(in.error());
  image::FoveateParams p;
  p.sigma = a.sigma;
  p.fx = a.fx;
  p.fy = a.fy;
  p.fovea_x = fovea->first;
  p.fovea_y = fovea->second;
  auto r = image::foveate(*in, p);
  if (!r) return cli::report(r.error());
  if (Status s = image::save_png(a.out, r->output); !s) return cli::report(s.error());
  if (!a.reduced_out.empty())
    if (Status s = image::save_png(a.reduced_out, r->reduced); !s) return cli::report(s.error());
  const double psnr = image::psnr(*in, r->output);
  if (a.json) {
    cli::print_json({{"in", a.in}, {"out", a.out}, {"method", a.method}, {"size", {in->width, in->height}},
                     {"buffer", {r->reduced.width, r->reduced.height}}, {"sigma", a.sigma}, {"fx", a.fx}, {"fy", a.fy},
                     {"fovea", {p.fovea_x, p.fovea_y}}, {"psnr_db", std::isfinite(psnr) ? nlohmann::json(psnr) : nlohmann::json("inf")}});
  } else {
    std::printf("%s (%dx%d) -> %dx%d buffer -> %s, PSNR %.2f dB\n", a.in.c_str(), in->width, in->height, r->reduced.width,
                r->reduced.height, a.out.c_str(), psnr);
  }
  return cli::kExitOk;
}

}  // namespace

void add_foveate(CLI::App& app, int& exit_code) {
  auto args = std::make_shared<Args>();
  CLI::App* sub = app.add_subcommand("foveate", "Apply RMFR's mapping to an image (forward with prefilter, then inverse)");
  sub->add_option("--in,-i", args->in, "Input image (PNG, JPEG, BMP, TGA)")->required();
  sub->add_option("--out,-o", args->out, "Output PNG at the input's size")->required();
  sub->add_option("--reduced-out", args->reduced_out, "Also write the reduced w×h buffer here");
  sub->add_option("--method", args->method, "Foveation method")->check(CLI::IsMember({"rmfr"}))->capture_default_str();
  sub->add_option("--sigma", args->sigma, "Level: W/w = H/h (>= 1)")->capture_default_str();
  sub->add_option("--fx", args->fx, "f along x, a fraction of the width (> 0)")->capture_default_str();
  sub->add_option("--fy", args->fy, "f along y, a fraction of the height (> 0)")->capture_default_str();
  sub->add_option("--fovea", args->fovea, "Fovea X,Y in [0,1], origin top-left")->capture_default_str();
  sub->add_flag("--json", args->json, "Print sizes and PSNR against the input as JSON");
  sub->callback([args, &exit_code] { exit_code = run(*args); });
}

}  // namespace foveal::cmd
