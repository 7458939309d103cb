// What the command line prints after a run (here, so that the CLI sees only pipeline).
#include "pipeline/summary.hpp"
#include <cstdio>
#include <ostream>

namespace fdr::pipeline {

void write_summary(const Result& r, std::ostream& out) {
  quality::write_text(r.report, out);
  write_stages_and_outputs(r.stages, r.written, out);
}

void write_stages_and_outputs(const std::vector<StageTime>& stages, const std::vector<std::string>& written,
                              std::ostream& out) {
  out << "stages (s, peak MiB):";
  for (const auto& st : stages) {
    char buf[96];
    std::snprintf(buf, sizeof buf, " %s %.2f (%.0f)", st.name.c_str(), st.seconds, st.peak_rss_mb);
    out << buf;
  }
  out << "\n";
  for (const auto& w : written) out << "wrote " << w << "\n";
  out.flush();
}

}  // namespace fdr::pipeline
