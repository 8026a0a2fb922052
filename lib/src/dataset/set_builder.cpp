#include "mocapdb/dataset/set_builder.hpp"

#include <algorithm>

#include "mocapdb/core/error.hpp"

namespace mocapdb {
namespace {

std::size_t parse_count(const std::string& text, const std::string& spec) {
    std::size_t used = 0;
    unsigned long long value = 0;
    try {
        value = std::stoull(text, &used);
    } catch (const std::logic_error&) {
        used = 0;
    }
    if (used != text.size() || value < 1)
        throw InvalidArgument("segmentation '" + spec + "': '" + text + "' is not a positive count");
    return static_cast<std::size_t>(value);
}

double parse_seconds(const std::string& text, const std::string& spec) {
    std::size_t used = 0;
    double value = -1.0;
    try {
        value = std::stod(text, &used);
    } catch (const std::logic_error&) {
        used = 0;
    }
    if (used != text.size() || !(value >= 0.0 && value <= 60.0))
        throw InvalidArgument("segmentation '" + spec + "': '" + text + "' is not a duration in seconds (0 to 60)");
    return value;
}

}  // namespace

void parse_segmentation(const std::string& spec, SetBuildOptions& options) {
    if (spec == "auto") {
        options.segmentation = Segmentation::Auto;
    } else if (spec.empty() || spec == "none") {
        options.segmentation = Segmentation::WholeClips;
    } else if (spec == "gait" || spec.rfind("gait:", 0) == 0) {
        options.segmentation = Segmentation::GaitCycles;
        options.gait.max_per_clip = spec == "gait" ? 0 : parse_count(spec.substr(5), spec);
    } else if (spec.rfind("window:", 0) == 0) {
        const std::string rest = spec.substr(7);
        const auto colon = rest.find(':');
        options.segmentation = Segmentation::Windows;
        options.window_length = parse_count(rest.substr(0, colon), spec);
        options.window_hop =
            colon == std::string::npos ? options.window_length : parse_count(rest.substr(colon + 1), spec);
        if (options.window_length < 2)
            throw InvalidArgument("segmentation '" + spec + "': windows need at least 2 frames");
    } else if (spec == "flight" || spec.rfind("flight:", 0) == 0) {
        options.segmentation = Segmentation::Flights;
        if (spec != "flight") {
            const std::string rest = spec.substr(7);
            const auto colon = rest.find(':');
            options.flight.before_seconds = parse_seconds(rest.substr(0, colon), spec);
            if (colon != std::string::npos) options.flight.after_seconds = parse_seconds(rest.substr(colon + 1), spec);
        }
    } else {
        throw InvalidArgument("unknown segmentation '" + spec +
                              "' (expected auto, none, gait[:N], window:LENGTH[:HOP] or flight[:BEFORE[:AFTER]])");
    }
}

namespace {

// The set's samples and parameters over every clip with a resolved segmentation (not Auto).
void collect_samples(const std::vector<std::string>& clip_ids, const ClipLoader& load, const SetBuildOptions& options,
                     Segmentation segmentation, MotionSet& set, std::vector<VecX>& rows,
                     std::vector<std::string>* out_skipped) {
    std::uint64_t done = 0;
    for (const std::string& id : clip_ids) {
        Clip clip = load(id);
        std::vector<DropoutRun> dropouts;
        if (options.repair_dropouts) {
            dropouts = detect_dropouts(clip, options.dropout);
            repair_dropouts(clip, dropouts);
        }
        std::vector<SampleRef> samples;
        switch (segmentation) {
            case Segmentation::Auto:  // resolved by the caller
            case Segmentation::WholeClips: samples = {{id, 0, clip.frame_count()}}; break;
            case Segmentation::GaitCycles: samples = gait_cycles(clip, id, options.gait); break;
            case Segmentation::Windows:
                samples = fixed_windows(clip, id, options.window_length, options.window_hop);
                break;
            case Segmentation::Flights: samples = flight_window(clip, id, options.flight); break;
        }
        if (samples.empty() && out_skipped) out_skipped->push_back(id);
        if (!samples.empty())
            for (RepairedFrames& r : repair_records(id, dropouts)) set.repairs.push_back(std::move(r));
        for (const SampleRef& s : samples) {
            try {
                rows.push_back(extract_parameters(clip, s.begin, s.end, options.extractors));
            } catch (const InvalidArgument& e) {
                throw InvalidArgument("motion set '" + options.name + "', sample " +
                                      sample_label(s, clip.frame_count()) + ": " + e.what());
            }
            set.samples.push_back(s);
        }
        if (options.progress) options.progress({++done, clip_ids.size(), id});
    }
}

}  // namespace

MotionSet build_motion_set(const std::vector<std::string>& clip_ids, const ClipLoader& load,
                           const SetBuildOptions& options, std::vector<std::string>* out_skipped,
                           Segmentation* out_used) {
    if (clip_ids.empty()) throw InvalidArgument("motion set '" + options.name + "': no clips selected");
    MotionSet set;
    set.name = options.name;
    std::vector<double> periods;
    for (const ParameterExtractor& e : options.extractors) {
        for (const std::string& n : e.names()) set.parameter_names.push_back(n);
        for (const std::string& u : e.units()) set.parameter_units.push_back(u);
        for (const double t : e.periods()) periods.push_back(t);
    }
    if (std::any_of(periods.begin(), periods.end(), [](double t) { return t > 0.0; }))
        set.parameter_periods = Eigen::Map<const VecX>(periods.data(), static_cast<Eigen::Index>(periods.size()));
    set.dropouts_checked = options.repair_dropouts;
    std::vector<VecX> rows;
    Segmentation used = options.segmentation;
    const bool measures_jumps = std::any_of(options.extractors.begin(), options.extractors.end(),
                                            [](const ParameterExtractor& e) { return e.kind == ParameterKind::Jump; });
    if (used == Segmentation::Auto && measures_jumps) used = Segmentation::Flights;
    if (used == Segmentation::Auto) {
        used = Segmentation::WholeClips;
        // Locomotion is told by the feet: gait cycles when most clips have one (the others, e.g. a
        // walk that stops after one step, are left out and listed, as with explicit gait cycles).
        if (!options.extractors.empty()) {
            std::vector<std::string> without_cycle;
            bool cycles = false;
            try {
                collect_samples(clip_ids, load, options, Segmentation::GaitCycles, set, rows, &without_cycle);
                cycles = static_cast<double>(without_cycle.size()) <=
                         (1.0 - kAutoGaitShare) * static_cast<double>(clip_ids.size());
            } catch (const InvalidArgument&) {
                cycles = false;  // no feet found by name, or a cycle's parameters undefined: whole clips
            }
            if (cycles) {
                used = Segmentation::GaitCycles;
                if (out_skipped) *out_skipped = without_cycle;
            }
        }
        if (used == Segmentation::WholeClips) {
            set.samples.clear();
            set.repairs.clear();
            rows.clear();
            collect_samples(clip_ids, load, options, used, set, rows, nullptr);
        }
    } else {
        collect_samples(clip_ids, load, options, used, set, rows, out_skipped);
    }
    if (out_used) *out_used = used;
    if (set.samples.empty())
        throw InvalidArgument("motion set '" + options.name + "': the " + std::to_string(clip_ids.size()) +
                              " selected clips yield no sample");
    set.parameters.resize(static_cast<Eigen::Index>(rows.size()),
                          static_cast<Eigen::Index>(set.parameter_names.size()));
    if (set.parameters.cols() > 0)  // (no columns: the caller supplies the parameters, e.g. from a CSV)
        for (std::size_t i = 0; i < rows.size(); ++i)
            set.parameters.row(static_cast<Eigen::Index>(i)) = rows[i].transpose();
    if (!options.extractors.empty()) {
        set.parameter_source = "extract:";
        for (std::size_t k = 0; k < options.extractors.size(); ++k)
            set.parameter_source += (k ? "," : "") + options.extractors[k].spec();
    }
    return set;
}

Clip sample_frames(const MotionSet& set, std::size_t index, const Clip& clip) {
    if (index >= set.samples.size())
        throw InvalidArgument("motion set '" + set.name + "': sample " + std::to_string(index) + " out of range (" +
                              std::to_string(set.samples.size()) + " samples)");
    const SampleRef& s = set.samples[index];
    if (s.end > clip.frame_count() || s.begin >= s.end)
        throw InvalidArgument("motion set '" + set.name + "': sample " + std::to_string(index) + " (" + s.clip +
                              " frames [" + std::to_string(s.begin) + ", " + std::to_string(s.end) +
                              ")) lies beyond the clip's " + std::to_string(clip.frame_count()) + " frames");
    return slice(with_repairs(clip, s.clip, set.repairs), s.begin, s.end);
}

std::string sample_label(const SampleRef& sample, std::size_t clip_frames) {
    if (sample.begin == 0 && sample.end == clip_frames) return sample.clip;
    return sample.clip + ":" + std::to_string(sample.begin) + "-" + std::to_string(sample.end);
}

}  // namespace mocapdb
