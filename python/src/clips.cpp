// Skeletons and clips: channels, pose vectors and forward kinematics as numpy arrays; reading BVH and
// ASF/AMC files, writing BVH.
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <array>
#include <memory>
#include <optional>

#include "arrays.hpp"
#include "bindings.hpp"
#include "mocapdb/io/bvh.hpp"
#include "mocapdb/io/clip_file.hpp"
#include "mocapdb/motion/clip.hpp"
#include "mocapdb/motion/forward_kinematics.hpp"
#include "mocapdb/motion/pose_vector.hpp"

namespace mocapdb::python {
namespace {

/// pybind11 holders are of non-const types; the library's skeletons are immutable anyway.
using SkeletonPtr = std::shared_ptr<Skeleton>;

/// Global joint positions of every frame into a new (F, J, 3) array, without the GIL.
Array joint_positions_array(const Clip& clip) {
    const std::size_t frames = clip.frame_count(), joints = clip.skeleton->size();
    Array out({frames, joints, std::size_t{3}});
    double* data = out.mutable_data();
    {
        py::gil_scoped_release release;
        GlobalPose pose;
        for (std::size_t f = 0; f < frames; ++f) {
            forward_kinematics(*clip.skeleton, clip.frame(f), pose);
            double* row = data + f * joints * 3;
            for (std::size_t j = 0; j < joints; ++j) {
                row[3 * j] = pose.positions[j].x();
                row[3 * j + 1] = pose.positions[j].y();
                row[3 * j + 2] = pose.positions[j].z();
            }
        }
    }
    return out;
}

Clip make_clip(const SkeletonPtr& skeleton, const Array& channels, double frame_rate, const std::string& name) {
    if (!skeleton) throw InvalidArgument("Clip: a skeleton is required");
    if (channels.ndim() != 2 || channels.shape(1) != static_cast<py::ssize_t>(skeleton->channel_count()))
        throw InvalidArgument("Clip: expected channels of shape (frames, " + std::to_string(skeleton->channel_count()) + ")");
    Clip clip;
    clip.skeleton = skeleton;
    clip.frame_rate = frame_rate;
    clip.name = name;
    clip.channels = Eigen::Map<const FrameMatrix>(channels.data(), channels.shape(0), channels.shape(1));
    validate(clip);
    return clip;
}

PositionChannels position_mode(const std::string& text) {
    const auto mode = position_channels_from_string(text);
    if (!mode) throw InvalidArgument("bvh_positions: expected 'replace_offset' or 'add_to_offset', got '" + text + "'");
    return *mode;
}

void write_bvh_file(const Clip& clip, const std::filesystem::path& path, int precision) {
    BvhWriteOptions options;
    options.precision = precision;
    write_bvh(path, clip, options);
}

/// A skeleton's whole definition as plain Python values (pickle's state): per joint (name, parent,
/// offset, channel types, rotation order, ASF axis w x y z, end site), then source units, forward,
/// position-channel mode and motion root.
py::tuple skeleton_state(const Skeleton& s) {
    py::list joints;
    for (const Joint& j : s.joints()) {
        py::list channels;
        for (ChannelType c : j.channels) channels.append(static_cast<int>(c));
        joints.append(py::make_tuple(j.name, j.parent, py::make_tuple(j.offset.x(), j.offset.y(), j.offset.z()), channels,
                                     static_cast<int>(j.rotation_order),
                                     py::make_tuple(j.axis.w(), j.axis.x(), j.axis.y(), j.axis.z()), j.end_site));
    }
    const Vec3& f = s.forward();
    return py::make_tuple(joints, py::make_tuple(s.source_units().cm_per_unit, s.source_units().degrees),
                          py::make_tuple(f.x(), f.y(), f.z()), to_string(s.position_channels()), s.motion_root());
}

SkeletonPtr skeleton_from_state(const py::tuple& t) {
    if (t.size() != 5) throw InvalidArgument("Skeleton: not a pickled skeleton's state");
    std::vector<Joint> joints;
    for (const py::handle item : t[0].cast<py::list>()) {
        const auto j = item.cast<py::tuple>();
        Joint joint;
        joint.name = j[0].cast<std::string>();
        joint.parent = j[1].cast<int>();
        const auto o = j[2].cast<std::array<double, 3>>();
        joint.offset = Vec3(o[0], o[1], o[2]);
        for (int c : j[3].cast<std::vector<int>>()) joint.channels.push_back(static_cast<ChannelType>(c));
        joint.rotation_order = static_cast<EulerOrder>(j[4].cast<int>());
        const auto q = j[5].cast<std::array<double, 4>>();
        joint.axis = Quat(q[0], q[1], q[2], q[3]);
        joint.end_site = j[6].cast<bool>();
        joints.push_back(std::move(joint));
    }
    const auto units = t[1].cast<std::pair<double, bool>>();
    const auto f = t[2].cast<std::array<double, 3>>();
    return std::make_shared<Skeleton>(std::move(joints), SourceUnits{units.first, units.second}, Vec3(f[0], f[1], f[2]),
                                      position_mode(t[3].cast<std::string>()), t[4].cast<std::size_t>());
}

}  // namespace

void bind_clips(py::module_& m) {
    py::class_<Skeleton, SkeletonPtr>(m, "Skeleton", "A rig: joints (end sites included) with parents, offsets and channels." "\n\nExample:\n    >>> skeleton = mocapdb.read_clip('16_11.amc').skeleton\n    >>> skeleton.joint_names[:2], len(skeleton)")
        .def_property_readonly(
            "joint_names",
            [](const Skeleton& s) {
                std::vector<std::string> names;
                for (const Joint& j : s.joints()) names.push_back(j.name);
                return names;
            },
            "Joint names in skeleton order (the J of joint positions).")
        .def_property_readonly(
            "parents",
            [](const Skeleton& s) {
                std::vector<int> parents;
                for (const Joint& j : s.joints()) parents.push_back(j.parent);
                return parents;
            },
            "Parent index of each joint (-1 for the root).")
        .def_property_readonly(
            "end_sites",
            [](const Skeleton& s) {
                std::vector<bool> ends;
                for (const Joint& j : s.joints()) ends.push_back(j.end_site);
                return ends;
            },
            "True for the joints that are end sites.")
        .def_property_readonly(
            "offsets",
            [](const Skeleton& s) {
                FrameMatrix o(static_cast<Eigen::Index>(s.size()), 3);
                for (std::size_t j = 0; j < s.size(); ++j) o.row(static_cast<Eigen::Index>(j)) = s.joint(j).offset.transpose();
                return copy_rows(o);
            },
            "(J, 3) rest offsets from the parent, cm.")
        .def_property_readonly(
            "channel_names",
            [](const Skeleton& s) {
                std::vector<std::string> names;
                for (const Joint& j : s.joints())
                    for (ChannelType c : j.channels) names.push_back(j.name + "." + to_string(c));
                return names;
            },
            "One name per channel column, 'Joint.Xrotation' (positions cm, rotations radians).")
        .def_property_readonly("channel_count", &Skeleton::channel_count, "C, channels per frame.")
        .def_property_readonly(
            "pose_values", [](const Skeleton& s) { return PoseLayout(s).dof_count(); },
            "D, values per pose vector (6 for the motion root, 3 per other rotating joint).")
        .def(
            "channels_from_pose_vectors",
            [](const Skeleton& s, const Array& poses) {
                const Eigen::Index d = static_cast<Eigen::Index>(PoseLayout(s).dof_count());
                const auto view = transposed_view(poses, d, "channels_from_pose_vectors");
                return copy_rows(from_pose_vectors(s, view, Canonicalization{}));
            },
            py::arg("poses"),
            "Channel rows (F, C) of pose vectors (F, D) in the canonical frame: the inverse of "
            "Clip.pose_vectors(canonical=False).")
        .def("__len__", &Skeleton::size)
        .def("__repr__", [](const Skeleton& s) {
            return "<mocapdb.Skeleton " + std::to_string(s.size()) + " joints, " + std::to_string(s.channel_count()) + " channels>";
        })
        .def(py::pickle(&skeleton_state, &skeleton_from_state));

    py::class_<Clip, std::shared_ptr<Clip>>(m, "Clip", "One motion: a skeleton, a frame rate and a row of channels per frame." "\n\nExample:\n    >>> clip = mocapdb.read_clip('16_11.amc')\n    >>> clip.channels.shape, clip.joint_positions().shape   # (F, C), (F, J, 3)")
        .def(py::init([](const SkeletonPtr& skeleton, const Array& channels, double frame_rate, const std::string& name) {
                 return std::make_shared<Clip>(make_clip(skeleton, channels, frame_rate, name));
             }),
             py::arg("skeleton"), py::arg("channels"), py::arg("frame_rate"), py::arg("name") = "",
             "A clip of the skeleton from channel rows (F, C) in cm and radians; InvalidArgument for a wrong "
             "shape, a non-positive rate or a non-finite value.")
        .def_readonly("name", &Clip::name, "Where it came from (the clip id or file stem).")
        .def_readonly("frame_rate", &Clip::frame_rate, "Frames per second.")
        .def_property_readonly("frames", &Clip::frame_count, "F, the number of frames.")
        .def_property_readonly("duration", &Clip::duration, "Seconds from the first to the last frame.")
        .def_property_readonly(
            "skeleton", [](const Clip& c) { return std::const_pointer_cast<Skeleton>(c.skeleton); }, "Its Skeleton.")
        .def_property_readonly(
            "channels", [](const Clip& c) { return copy_rows(c.channels); },
            "(F, C) channel values, positions in cm and rotations in radians (a copy).")
        .def("joint_positions", &joint_positions_array,
             "Global joint positions (F, J, 3) in cm by forward kinematics, every joint and end site "
             "(Skeleton.joint_names order); the GIL is released.")
        .def(
            "pose_vectors",
            [](const Clip& c, bool canonical) {
                const Canonicalization frame = canonical ? canonicalization_of(c) : Canonicalization{};
                MatX poses;
                {
                    py::gil_scoped_release release;
                    poses = to_pose_vectors(c, frame);
                }
                return copy_columns(poses);
            },
            py::arg("canonical") = true,
            "Pose vectors (F, D): the motion root's position (cm) and heading-relative orientation, then "
            "every other rotating joint's local rotation as an exponential map. canonical: first frame at "
            "the origin facing +Z (else the world frame).")
        .def(
            "slice", [](const Clip& c, std::size_t begin, std::size_t end) { return slice(c, begin, end); },
            py::arg("begin"), py::arg("end"), "Frames [begin, end) as a clip of their own.")
        .def("write_bvh", &write_bvh_file, py::arg("path"), py::arg("precision") = 9,
             "Writes the clip as BVH (atomically; an existing file is replaced). precision: significant digits "
             "(17 is lossless).")
        .def("__len__", &Clip::frame_count)
        .def("__repr__", [](const Clip& c) {
            return "<mocapdb.Clip '" + c.name + "' " + std::to_string(c.frame_count()) + " frames at " +
                   std::to_string(c.frame_rate) + " Hz>";
        })
        .def(py::pickle(
            [](const Clip& c) {
                return py::make_tuple(std::const_pointer_cast<Skeleton>(c.skeleton), copy_rows(c.channels), c.frame_rate, c.name);
            },
            [](const py::tuple& t) {
                if (t.size() != 4) throw InvalidArgument("Clip: not a pickled clip's state");
                return std::make_shared<Clip>(make_clip(t[0].cast<SkeletonPtr>(), t[1].cast<Array>(), t[2].cast<double>(),
                                                        t[3].cast<std::string>()));
            }));

    m.def(
        "read_clip",
        [](const std::filesystem::path& path, std::optional<std::filesystem::path> asf, std::optional<double> frame_rate,
           bool strict, const std::string& bvh_positions) {
            ClipReadOptions options;
            if (asf) options.asf = *asf;
            options.frame_rate = frame_rate;
            options.strict = strict;
            options.bvh_positions = position_mode(bvh_positions);
            Warnings warnings;
            Clip clip;
            {
                py::gil_scoped_release release;
                clip = read_clip(path, options, &warnings);
            }
            for (const Warning& w : warnings)
                if (PyErr_WarnEx(PyExc_UserWarning, w.to_string().c_str(), 1) != 0) throw py::error_already_set();
            return std::make_shared<Clip>(std::move(clip));
        },
        py::arg("path"), py::arg("asf") = py::none(), py::arg("frame_rate") = py::none(), py::arg("strict") = false,
        py::arg("bvh_positions") = "replace_offset",
        "Reads a .bvh file, or an .amc file with its .asf (found beside it by the CMU naming unless given). "
        "Defects the reader works around become UserWarnings (strict=True refuses them); ParseError names "
        "the file and line. bvh_positions: 'replace_offset' (position channels are the local translation) "
        "or 'add_to_offset'." "\n\nExample:\n    >>> clip = mocapdb.read_clip('16_11.amc')          # 16.asf beside it\n    >>> clip = mocapdb.read_clip('walk.bvh', strict=True)");
    m.def("write_bvh", &write_bvh_file, py::arg("clip"), py::arg("path"), py::arg("precision") = 9,
          "Writes a clip as BVH (atomically; an existing file is replaced)." "\n\nExample:\n    >>> mocapdb.write_bvh(mocapdb.read_clip('16_11.amc'), '16_11.bvh')");
}

}  // namespace mocapdb::python
