// gnuplot-driven force plots.
#include "plot/force_plot.h"

#include <cinttypes>
#include <cstdio>
#include <cstdlib>
#include <unordered_map>

#include "transport/output_file.h"

namespace birotor {

bool WriteForcePlot(const std::vector<ForceEstimate>& forces, const std::vector<TruthSample>& truth,
                    const std::string& title, const std::string& png_path, std::string* error) {
  std::unordered_map<int64_t, size_t> truth_index;
  for (size_t i = 0; i < truth.size(); ++i) truth_index[truth[i].utime] = i;
  const std::string data_path = png_path + ".dat";
  const std::string script_path = png_path + ".gp";
  std::FILE* data = std::fopen(data_path.c_str(), "w");
  if (data == nullptr) {
    *error = "cannot write " + data_path;
    return false;
  }
  std::fprintf(data, "# t_s f1_est f2_est f1_true f2_true err1 err2 std1 std2\n");
  int64_t rows = 0;
  for (const ForceEstimate& e : forces) {
    auto it = truth_index.find(e.utime);
    if (it == truth_index.end()) continue;
    const TruthSample& t = truth[it->second];
    std::fprintf(data, "%.6f %.6g %.6g %.6g %.6g %.6g %.6g %.6g %.6g\n", static_cast<double>(e.utime) * 1e-6,
                 e.force_n[0], e.force_n[1], t.force_n[0], t.force_n[1], e.force_n[0] - t.force_n[0],
                 e.force_n[1] - t.force_n[1], e.force_std_n[0], e.force_std_n[1]);
    ++rows;
  }
  std::fclose(data);
  if (rows == 0) {
    *error = "no FORCE message pairs with a TRUTH message by utime";
    return false;
  }
  // gnuplot draws into a temporary file next to the PNG, renamed on success.
  OutputFile png;
  if (!png.Open(png_path, error)) return false;
  std::FILE* script = std::fopen(script_path.c_str(), "w");
  if (script == nullptr) {
    *error = "cannot write " + script_path;
    return false;
  }
  std::fprintf(script,
               "set terminal pngcairo size 1200,1000 noenhanced font ',10'\n"
               "set output '%s'\n"
               "set multiplot layout 3,1 title '%s'\n"
               "set grid\nset key top right\n"
               "set ylabel 'f1 [N]'\n"
               "plot '%s' u 1:4 w l lw 2 lc rgb '#404040' t 'true', "
               "'' u 1:2 w l lc rgb '#d62728' t 'estimated'\n"
               "set ylabel 'f2 [N]'\n"
               "plot '%s' u 1:5 w l lw 2 lc rgb '#404040' t 'true', "
               "'' u 1:3 w l lc rgb '#1f77b4' t 'estimated'\n"
               "set ylabel 'error [N]'\nset xlabel 't [s]'\n"
               "plot '%s' u 1:6 w l lc rgb '#d62728' t 'f1 est - true', "
               "'' u 1:7 w l lc rgb '#1f77b4' t 'f2 est - true'\n"
               "unset multiplot\n",
               png.write_path().c_str(), title.c_str(), data_path.c_str(), data_path.c_str(), data_path.c_str());
  std::fclose(script);
  const std::string command = "gnuplot '" + script_path + "'";
  if (std::system(command.c_str()) != 0) {
    *error = "gnuplot failed on " + script_path + " (is gnuplot with pngcairo installed?)";
    return false;
  }
  return png.Commit(error);
}

}  // namespace birotor
