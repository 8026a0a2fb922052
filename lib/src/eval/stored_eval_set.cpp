#include "mocapdb/eval/stored_eval_set.hpp"

#include "mocapdb/dataset/set_builder.hpp"
#include "mocapdb/store/database.hpp"
#include "mocapdb/workflow/aligned_set_data.hpp"
#include "mocapdb/workflow/synthesis_step.hpp"

namespace mocapdb::eval {

EvalSet load_eval_set(const Database& db, const std::string& name) {
    workflow::AlignedSetData data = workflow::load_aligned_set(db, name);
    EvalSet out;
    out.spec.name = name;
    out.spec.description = "set '" + name + "' of " + db.path().filename().string();
    out.spec.frames = data.aligned.frames();
    out.extractors = workflow::source_extractors(data.set.parameter_source);
    for (const ParameterExtractor& e : out.extractors) out.spec.extractors.push_back(e.spec());
    out.skeleton = std::move(data.skeleton);
    out.frame_rate = data.frame_rate;
    out.aligned = std::move(data.aligned);
    out.set = std::move(data.set);
    std::string loaded;  // samples of one clip are consecutive: one clip read at a time
    Clip clip;
    for (std::size_t i = 0; i < out.set.samples.size(); ++i) {
        const SampleRef& s = out.set.samples[i];
        if (s.clip != loaded) {
            clip = db.load_clip(s.clip);
            loaded = s.clip;
            out.clip_ids.push_back(s.clip);
        }
        Clip sample = sample_frames(out.set, i, clip);
        sample.name = sample_label(s, clip.frame_count());
        out.labels.push_back(sample.name);
        out.samples.push_back(std::move(sample));
    }
    return out;
}

}  // namespace mocapdb::eval
