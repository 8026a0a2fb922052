#include "mocapdb/workflow/synthesis_step.hpp"

#include <algorithm>
#include <chrono>

#include "mocapdb/core/error.hpp"

namespace mocapdb::workflow {

std::vector<ParameterExtractor> source_extractors(const std::string& source) {
    std::vector<ParameterExtractor> ex;
    const std::string prefix = "extract:";
    std::size_t part = 0;  // parts "extract:...; csv:...; category:..." (older sets: one part)
    while (part < source.size() && source.compare(part, prefix.size(), prefix) != 0) {
        const std::size_t next = source.find("; ", part);
        if (next == std::string::npos) return ex;
        part = next + 2;
    }
    if (part >= source.size()) return ex;
    const std::size_t part_end = source.find(';', part);
    const std::string rest = source.substr(
        part + prefix.size(), part_end == std::string::npos ? std::string::npos : part_end - part - prefix.size());
    std::size_t start = 0;
    while (start <= rest.size()) {
        const std::size_t comma = rest.find(',', start);
        const std::string spec = rest.substr(start, comma == std::string::npos ? std::string::npos : comma - start);
        if (!spec.empty()) ex.push_back(ParameterExtractor::parse(spec));
        if (comma == std::string::npos) break;
        start = comma + 1;
    }
    return ex;
}

std::vector<ParameterExtractor> applicable_extractors(const MotionSet& set) {
    std::vector<ParameterExtractor> ex;
    for (const char* spec : {"displacement", "turn", "speed", "bearing"}) ex.push_back(ParameterExtractor::parse(spec));
    for (const ParameterExtractor& e : source_extractors(set.parameter_source)) {
        const bool listed =
            std::any_of(ex.begin(), ex.end(), [&](const ParameterExtractor& x) { return x.spec() == e.spec(); });
        if (!listed) ex.push_back(e);
    }
    return ex;
}

SynthOutcome synthesize(const synthesis::SynthesisModel& model, const MotionSet& set, const VecX& c,
                        Eigen::Index level) {
    SynthOutcome o;
    o.requested = c;
    const auto start = std::chrono::steady_clock::now();
    o.timing = model.timing(c);
    o.clip = model.motion(c, level);
    o.reliability = model.reliability(c);
    o.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (o.clip.frame_count() >= 2)
        for (const ParameterExtractor& e : applicable_extractors(set)) {
            VecX values;
            try {
                values = extract_parameters(o.clip, 0, o.clip.frame_count(), {e});
            } catch (const InvalidArgument&) {
                continue;  // undefined on this motion (no travel for a bearing, no flight for a jump)
            }
            const std::vector<std::string> names = e.names(), units = e.units();
            for (Eigen::Index k = 0; k < values.size(); ++k)
                o.measurements.push_back(
                    {names[static_cast<std::size_t>(k)], units[static_cast<std::size_t>(k)], values(k)});
        }
    // A parameter's measurement: the column of the extractor that measured it (CSV and categories: none).
    std::vector<std::string> extracted;
    for (const ParameterExtractor& e : source_extractors(set.parameter_source))
        for (const std::string& n : e.names()) extracted.push_back(n);
    for (const std::string& name : set.parameter_names) {
        std::optional<double> value;
        if (std::find(extracted.begin(), extracted.end(), name) != extracted.end())
            for (const Measurement& m : o.measurements)
                if (m.name == name) value = m.value;
        o.parameter_measured.push_back(value);
    }
    if (std::all_of(o.parameter_measured.begin(), o.parameter_measured.end(),
                    [](const auto& v) { return v.has_value(); })) {
        o.measured.resize(static_cast<Eigen::Index>(o.parameter_measured.size()));
        for (std::size_t p = 0; p < o.parameter_measured.size(); ++p)
            o.measured(static_cast<Eigen::Index>(p)) = *o.parameter_measured[p];
    }
    return o;
}

}  // namespace mocapdb::workflow
