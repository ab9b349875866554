#pragma once
// Each `foveal` subcommand lives in its own commands/cmd_*.cpp, which parses its options
// and calls the code of its job (tools/README.md); it is declared here and added in
// main.cpp. A command's callback stores its exit code in `exit_code`.
namespace CLI {
class App;
}

namespace foveal::cmd {

void add_import(CLI::App& app, int& exit_code);
void add_log(CLI::App& app, int& exit_code);
void add_log_quality(CLI::App& log, int& exit_code);  // `log quality`, called by add_log
void add_log_plot(CLI::App& log, int& exit_code);     // `log plot`, called by add_log
void add_synth(CLI::App& app, int& exit_code);
void add_hid(CLI::App& app, int& exit_code);  // with FOVEAL_HAVE_HID
void add_profile(CLI::App& app, int& exit_code);
void add_service(CLI::App& app, int& exit_code);
void add_ctl(CLI::App& app, int& exit_code);
void add_calibrate(CLI::App& app, int& exit_code);
void add_replay(CLI::App& app, int& exit_code);
void add_predict_eval(CLI::App& app, int& exit_code);
void add_filter_chart(CLI::App& app, int& exit_code);
void add_render(CLI::App& app, int& exit_code);
void add_foveate(CLI::App& app, int& exit_code);
void add_metrics(CLI::App& app, int& exit_code);
void add_bench(CLI::App& app, int& exit_code);
void add_bench_merge(CLI::App& bench, int& exit_code);  // `bench merge`, called by add_bench
void add_outputs(CLI::App& app, int& exit_code);
void add_devices(CLI::App& app, int& exit_code);
void add_record(CLI::App& app, int& exit_code);
void add_study(CLI::App& app, int& exit_code);
void add_study_run(CLI::App& study, int& exit_code);  // `study run`, called by add_study
void add_openxr(CLI::App& app, int& exit_code);  // with FOVEAL_HAVE_OPENXR

}  // namespace foveal::cmd
