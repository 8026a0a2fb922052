#include "reference_database.hpp"

#include "mocapdb/compression/dof_weights.hpp"
#include "mocapdb/compression/joint_error.hpp"
#include "mocapdb/store/database.hpp"
#include "mocapdb/workflow/pack_collection.hpp"
#include "mocapdb/store/sha256.hpp"

namespace mocapdb::test {

ReferenceContent reference_content() {
    ReferenceContent r;
    Joint root;
    root.name = "hips";
    root.offset = Vec3(0.0, 90.0, 0.0);
    root.channels = {ChannelType::Xposition, ChannelType::Yposition, ChannelType::Zposition,
                     ChannelType::Zrotation, ChannelType::Xrotation, ChannelType::Yrotation};
    root.rotation_order = EulerOrder::ZXY;
    Joint spine;
    spine.name = "spine";
    spine.parent = 0;
    spine.offset = Vec3(0.0, 10.0, 0.0);
    spine.channels = {ChannelType::Zrotation, ChannelType::Xrotation, ChannelType::Yrotation};
    spine.rotation_order = EulerOrder::ZXY;
    Joint head;
    head.name = "head";
    head.parent = 1;
    head.offset = Vec3(0.0, 5.0, 0.0);
    head.end_site = true;
    r.clip.skeleton = std::make_shared<const Skeleton>(std::vector<Joint>{root, spine, head}, SourceUnits{1.0, true});
    r.clip.frame_rate = 30.0;
    r.clip.name = "tiny_walk";
    r.clip.channels = FrameMatrix(4, 9);
    for (Eigen::Index f = 0; f < 4; ++f)
        for (Eigen::Index c = 0; c < 9; ++c)
            r.clip.channels(f, c) = c < 3 ? 10.0 * static_cast<double>(f) + static_cast<double>(c)
                                          : 0.01 * static_cast<double>(c) * static_cast<double>(f + 1);
    r.source.file_name = "tiny_walk.bvh";
    r.source.sha256 = sha256_hex("mocapdb reference clip, format version 1");
    r.source.format = "bvh";
    r.source.subject = "reference";
    r.source.description = "tiny walk";
    r.source.labels = {"walk", "test"};

    r.set.name = "tiny_set";
    r.set.samples = {{"tiny_walk", 0, 3}, {"tiny_walk", 1, 4}};
    r.set.parameter_names = {"speed"};
    r.set.parameter_units = {"cm/s"};
    r.set.parameters = MatX(2, 1);
    r.set.parameters << 10.0, 12.0;
    r.set.parameter_source = "csv:reference.csv";

    AlignedSet& a = r.aligned;
    a.method = "linear";
    a.reference = 0;
    a.tensor = Tensor3(9, 3, 2);
    for (Eigen::Index s = 0; s < 2; ++s)
        for (Eigen::Index t = 0; t < 3; ++t)
            for (Eigen::Index d = 0; d < 9; ++d)
                a.tensor(d, t, s) = static_cast<double>(d) + 10.0 * static_cast<double>(t) + 100.0 * static_cast<double>(s);
    a.warps = MatX(3, 2);
    a.warps << 0.0, 0.0, 1.0, 1.0, 2.0, 2.0;
    a.mean = VecX::LinSpaced(9, 0.0, 4.0);
    a.scale = VecX::LinSpaced(9, 1.0, 9.0);
    for (int s = 0; s < 2; ++s) {
        Canonicalization c;
        c.translation = Vec3(static_cast<double>(s), 0.0, -static_cast<double>(s));
        c.yaw = 0.1 * static_cast<double>(s);
        a.canonical.push_back(c);
    }

    r.model = compression::fit_set_model(a.tensor, compression::position_error_weights(*r.clip.skeleton), {1, 2, 2},
                                         tensor::TuckerMethod::Hosvd);
    const compression::JointErrorStats e = compression::JointErrorMeter(r.clip.skeleton, a.tensor).measure(r.model.reconstruct());
    r.figures = {e.dof_rmse, e.rmse_cm, e.mean_cm, e.max_cm, e.p99_cm};
    return r;
}

void write_reference_database(const std::filesystem::path& path) {
    const ReferenceContent r = reference_content();
    DatabaseWriter w(path, DatabaseWriter::Mode::Create);
    w.add_clip(r.clip, r.source);
    w.put_set(r.set, false);
    w.put_aligned(r.set.name, r.aligned);
    w.put_model(r.set.name, r.model, r.figures);
    w.commit();
    workflow::PackDatabaseOptions o;
    o.max_error_cm = kReferencePackedErrorCm;
    o.threads = 1;
    workflow::pack_database(path, o);
}

}  // namespace mocapdb::test
