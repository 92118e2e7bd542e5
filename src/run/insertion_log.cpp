#include "run/insertion_log.hpp"

#include <filesystem>

#include "comm/rank_agreement.hpp"
#include "io/text_file.hpp"

namespace gs {
namespace {

// Shortfall warnings per inlet in the run log; later ones are in inlets.csv only.
constexpr int kWarningsPerInlet = 10;

}  // namespace

InsertionLog::InsertionLog(const SceneSpec& scene, const std::string& directory, Transport& transport)
    : scene_(scene), path_(directory + "/inlets.csv"), transport_(transport), warned_(scene.inlets.size(), 0) {
  written_by_rank_0(transport_, [&] {
    // A restart appends to the file of the run it continues.
    const bool fresh = !std::filesystem::exists(path_) || std::filesystem::file_size(path_) == 0;
    TextFile f(path_, "a");
    if (fresh) f.printf("step,time,inlet,count,mass,shortfall,total_count,total_mass\n");
    f.close();
  });
}

void InsertionLog::write(const std::vector<InsertionRecord>& records, const Log& log) {
  for (const InsertionRecord& r : records) {
    if (r.shortfall == 0) continue;
    int& warned = warned_[std::size_t(r.inlet)];
    if (warned++ >= kWarningsPerInlet) continue;
    const InletSpec& in = scene_.inlets[std::size_t(r.inlet)];
    log("warning: " + in.key + " (inlet '" + in.name + "'): step " + std::to_string(r.step) + ": " +
        std::to_string(r.shortfall) + " particle(s) due found no free place in " + std::to_string(in.attempts) +
        " attempts each; they stay due for the next batch" +
        (warned == kWarningsPerInlet ? " (further shortfalls of this inlet: inlets.csv only)" : "") + "\n");
  }
  written_by_rank_0(transport_, [&] {
    if (records.empty()) return;
    TextFile f(path_, "a");
    for (const InsertionRecord& r : records)
      f.printf("%lld,%.17g,%s,%llu,%.17g,%llu,%llu,%.17g\n", r.step, r.time,
               scene_.inlets[std::size_t(r.inlet)].name.c_str(), (unsigned long long)r.count, r.mass,
               (unsigned long long)r.shortfall, (unsigned long long)r.total.inserted, r.total.mass);
    f.close();
  });
}

}  // namespace gs
