// SPDX-License-Identifier: Apache-2.0
// stepnc roughness --nose-radius R --side-angle KR --end-angle KPR --feed F [--json]:
// the theoretical roughness a turning tool leaves at a feed (seed 001 4.2).
#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "command.h"
#include "stepnc/machining/roughness.h"

namespace stepnc::cli {
namespace {

struct RoughnessOptions {
  machining::TurningRoughnessInput input;
  bool json = false;
};

int run_roughness(const RoughnessOptions& options) {
  if (const std::string problem = machining::roughness_input_problem(options.input); !problem.empty()) {
    fmt::print(stderr, "error: {}\n", problem);
    return exit_invalid_input;
  }
  const machining::Roughness roughness = machining::surface_roughness(options.input);
  std::string text;
  if (options.json) {
    const nlohmann::ordered_json document{{"rt_mm", roughness.rt},
                                          {"ra_mm", roughness.ra},
                                          {"regime", machining::to_string(roughness.regime)}};
    text = document.dump(2) + "\n";
  } else {
    text = fmt::format("Rt {:.6g} mm\nRa {:.6g} mm (theoretical)\nregime {}\n", roughness.rt, roughness.ra,
                       machining::to_string(roughness.regime));
  }
  return write_outputs({{"-", text}});
}

}  // namespace

void add_roughness_command(CLI::App& app, Action& action) {
  auto options = std::make_shared<RoughnessOptions>();
  CLI::App* command =
      app.add_subcommand("roughness", "Theoretical roughness (Rt, Ra) a turning tool leaves at a feed (seed 001)");
  command->add_option("--nose-radius", options->input.nose_radius, "Nose radius r, mm (0: sharp tool)")->required();
  command->add_option("--side-angle", options->input.side_cutting_edge_deg,
                      "Side cutting edge angle K_r (ISO 3002 major angle, 95 for PCLNR), degrees")
      ->required();
  command->add_option("--end-angle", options->input.end_cutting_edge_deg, "End cutting edge angle K'_r, degrees")
      ->required();
  command->add_option("--feed", options->input.feed_per_revolution, "Feed, mm/rev")->required();
  command->add_flag("--json", options->json, "Print JSON");
  command->callback([&action, options] { action = [options] { return run_roughness(*options); }; });
}

}  // namespace stepnc::cli
