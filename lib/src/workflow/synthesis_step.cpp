#include "mocapdb/workflow/synthesis_step.hpp"

#include <chrono>

namespace mocapdb::workflow {

std::vector<ParameterExtractor> source_extractors(const std::string& source) {
    std::vector<ParameterExtractor> ex;
    const std::string prefix = "extract:";
    if (source.compare(0, prefix.size(), prefix) != 0) return ex;
    const std::string rest = source.substr(prefix.size());
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

SynthOutcome synthesize(const synthesis::SynthesisModel& model, const MotionSet& set, const VecX& c,
                        Eigen::Index level) {
    SynthOutcome o;
    o.requested = c;
    const auto start = std::chrono::steady_clock::now();
    o.timing = model.timing(c);
    o.clip = model.motion(c, level);
    o.reliability = model.reliability(c);
    o.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    // Measured parameters of the result, when the set's were measured by extractors.
    const std::vector<ParameterExtractor> ex = source_extractors(set.parameter_source);
    if (!ex.empty() && o.clip.frame_count() >= 2) {
        o.measured = extract_parameters(o.clip, 0, o.clip.frame_count(), ex);
        if (o.measured.size() != c.size()) o.measured.resize(0);
    }
    return o;
}

}  // namespace mocapdb::workflow
