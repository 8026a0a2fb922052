// REPORT.md of `mocapdb eval`, sections 4-8: sample reduction, foot skating, compression, run time and
// caveats (sections 1-3 and the assembly: eval_report.cpp); every number comes from EvalResults.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <sstream>

#include "eval_report_parts.hpp"

namespace mocapdb::cli::eval_report {

/// 4. Greedy sample reduction, per set.
void reduction_section(std::ostream& o, const EvalResults& e) {
    const RunInfo& info = e.info;
    o << "## 4. Sample reduction\n\n"
      << "Greedy removal of the sample whose leave-one-out reliability is highest (the geostatistical paper §5.2: 69 → 29 "
         "samples at τ = 0.85), continued past τ to draw the curve; at each kept size, the mean joint error (cm; pose and motion "
         "as in section 1) of predicting every removed sample from a naive kriging model of the kept ones, against random "
         "removal orders.\n\n";
    for (const SetResults& r : e.sets) {
        if (!r.has_reduction) continue;
        const eval::EvalSet& s = *r.set;
        o << "### " << s.spec.name << "\n\n"
          << "τ = " << fmt(r.reduction_options.tau) << " keeps **" << r.reduction.kept_at_tau << " of " << s.size()
          << "** samples";
        const eval::ReductionAtTau at_tau = eval::reduction_at_tau(r);
        if (at_tau == eval::ReductionAtTau::NothingRemoved)
            o << ": the highest leave-one-out reliability of any sample is already "
              << fixed(r.reduction.max_reliability.front(), 3) << " < τ, so "
              << "nothing is removed (the paper removes 40 of 69). With this set's fitted variogram no sample is "
              << "predicted reliably enough from the others; the curve below continues past τ to show what removal would cost";
        else if (at_tau == eval::ReductionAtTau::SomeRemoved) o << " (the paper: 29 of 69)";
        o << ".\n\n";
        Table rt{{"kept", "max LOO ρ", "greedy pose mean cm", "random pose mean cm", "greedy motion mean cm",
                  "greedy motion max cm", "random motion mean cm"},
                 {}};
        const bool rnd = r.reduction_options.random_orders > 0;
        for (const auto& p : r.reduction.points)
            rt.rows.push_back({std::to_string(p.kept), fixed(p.max_reliability, 3), fixed(p.greedy_pose_mean_cm, 2),
                               rnd ? fixed(p.random_pose_mean_cm, 2) : "-", fixed(p.greedy_mean_cm, 2),
                               fixed(p.greedy_max_cm, 1), rnd ? fixed(p.random_mean_cm, 2) : "-"});
        o << rt.str() << "\n"
          << caption(info, s,
                     "τ = " + fmt(r.reduction_options.tau) + ", " + std::to_string(r.reduction_options.random_orders) +
                         " random orders (seed " + std::to_string(r.reduction_options.seed) +
                         "), variogram fixed from all samples")
          << "\n![reduction](reduction_" << s.spec.name << ".svg)  \nNumbers: [reduction_" << s.spec.name
          << ".csv](reduction_" << s.spec.name << ".csv).\n\n";
    }
}

/// 5. Foot skating of the leave-one-out syntheses.
void skating_section(std::ostream& o, const EvalResults& e) {
    const RunInfo& info = e.info;
    o << "## 5. Foot skating\n\n"
      << "Horizontal travel of the feet (ltoes, rtoes) while in detected contact (height within 5 cm of the foot's floor "
         "level and speed below 40 cm/s, lib/include/mocapdb/eval/foot_skating.hpp), per second of contact, on the clips "
         "synthesized in the leave-one-out folds (with their synthesized timing), against the original samples. Because "
         "contacts require a low speed, this measures slow sliding within contacts; *contact* differences show up in the "
         "LOO errors instead.\n\n";
    {
        Table ft{{"set", "original"}, {}};
        std::vector<std::string> names;
        for (const SetResults& r : e.sets)
            if (r.has_loo)
                for (const auto& m : r.loo.methods)
                    if (std::find(names.begin(), names.end(), m.method) == names.end()) names.push_back(m.method);
        for (const auto& n : names) ft.header.push_back(n);
        for (const SetResults& r : e.sets) {
            if (!r.has_loo || r.loo.original_skating_cm_per_s.size() == 0) continue;
            std::vector<std::string> row{r.set->spec.name,
                                         fixed(eval::mean_if_any(r.loo.original_skating_cm_per_s), 2)};
            for (const auto& n : names) {
                std::string v = "-";
                for (const auto& m : r.loo.methods)
                    if (m.method == n && m.skating_cm_per_s.size()) v = fixed(eval::mean_if_any(m.skating_cm_per_s), 2);
                row.push_back(v);
            }
            ft.rows.push_back(row);
        }
        o << ft.str() << "\n"
          << short_caption(info, "the leave-one-out folds of section 1 (cm/s, mean over left-out samples)",
                           "contact height tolerance 5 cm, speed tolerance 40 cm/s, feet ltoes/rtoes")
          << "\nPer-sample values: the `skating_cm_per_s` columns of the loo_*.csv files.\n\n";
    }
}

/// 6. Compression (the rate-distortion report), per set.
void compression_section(std::ostream& o, const EvalResults& e) {
    const RunInfo& info = e.info;
    o << "## 6. Compression\n\n"
      << "The compression report of `mocapdb report` (lib/include/mocapdb/compression/rate_distortion.hpp) on each set's "
         "aligned tensor: per max joint-error target the cheapest setting of each method, its ranks, compression ratio "
         "(raw aligned float32 / bytes incl. side information), precompute seconds and µs per pose ('pose' = random access "
         "to one synthesized pose, 'stream' = decoding the whole set per pose), as the multilinear paper's Table 1.\n\n";
    for (const SetResults& r : e.sets) {
        if (!r.has_compression) continue;
        const eval::EvalSet& s = *r.set;
        o << "### " << s.spec.name << "\n\n";
        Table ct{
            {"method", "target", "ranks", "bytes", "ratio", "max cm", "rmse cm", "precompute s", "µs/pose", "access"},
            {},
            3};
        for (const auto& row : r.compression.rows)
            ct.rows.push_back(
                {row.method,
                 row.target_cm == 0.0 ? "lossless/raw"
                                      : "≤ " + fmt(row.target_cm) + " cm" + (row.target_met ? "" : " (not met)"),
                 ranks_text(row.ranks), std::to_string(row.bytes), fixed(row.ratio, 2), fmt(row.stats.max_cm),
                 fmt(row.stats.rmse_cm), fmt(row.precompute_s), fmt(row.us_per_pose), row.access});
        std::string targets;
        for (double tcm : r.compression_targets) targets += (targets.empty() ? "" : ", ") + fmt(tcm) + " cm";
        o << ct.str() << "\n"
          << caption(info, s,
                     "targets " + targets + "; raw aligned float32 " + std::to_string(r.compression.raw_bytes) +
                         " bytes; side information " + std::to_string(r.compression.side_bytes) +
                         " bytes charged to every row")
          << "\n![compression](compression_" << s.spec.name << ".svg)  \nNumbers: [compression_" << s.spec.name
          << ".csv](compression_" << s.spec.name << ".csv).\n\n";
    }
}

/// 7. Preprocessing and synthesis runtime.
void runtime_section(std::ostream& o, const EvalResults& e) {
    const RunInfo& info = e.info;
    o << "## 7. Runtime\n\n"
      << "Preprocessing (building the method on N samples) and synthesis (one whole aligned motion, divided by T) on "
         "evenly spread subsets of `"
      << e.runtime_set
      << "`, single thread, median of repeats (the geostatistical paper's "
         "Tables 1-2 report runtime and preprocessing per frame).\n\n";
    {
        Table rt{{"method", "N", "build s", "build µs per frame (÷ N·T)", "synthesis µs per frame"}, {}};
        for (const auto& row : e.runtime)
            rt.rows.push_back({row.method, std::to_string(row.samples), fmt(row.build_seconds),
                               fmt(row.build_us_per_frame), fmt(row.synth_us_per_frame)});
        const eval::EvalSet* rs = nullptr;
        for (const auto& r : e.sets)
            if (r.set->spec.name == e.runtime_set) rs = r.set.get();
        o << rt.str() << "\n";
        if (rs) o << caption(info, *rs, "wall-clock medians; load average at start " + info.load);
        o << "\n![synthesis time](runtime.svg) ![build time](runtime_build.svg)  \nNumbers: [runtime.csv](runtime.csv).\n\n";
    }
}

/// Caveats of the run.
void caveats_section(std::ostream& o, const EvalResults& e) {
    const RunInfo& info = e.info;
    o << "## Caveats\n\n"
      << "- The DTW alignment (reference sample, warps) is computed once per set with all samples; the leave-one-out folds "
         "refit everything else (variograms, trends, Tucker bases, timing kernels) without the left-out sample. The Tucker "
         "ranks of each tucker-Ecm method are chosen once on the whole set (the bases are refitted per fold at those ranks).\n"
      << "- Errors are measured in aligned time (synthesized aligned poses against the sample's aligned poses), so "
         "timing errors show only in the duration column, not in the joint errors.\n"
      << "- The regions of section 2 use one reliability map (naive kriging kernel) for every method, so RBF and the "
         "nearest-neighbour blend are judged on kriging's ρ.\n"
      << "- Timings are wall-clock on a shared 2-core machine (see the load average above) and single-threaded.\n"
      << "- The `jumps` set mixes three subjects on subject 13's skeleton (see Data).\n";
    if (info.mode != "full")
        o << "- This is a **" << info.mode << "** run: fewer sets, folds and grid points than the full report.\n";
}

}  // namespace mocapdb::cli::eval_report
