// Skeletons and clips: channels, pose vectors and forward kinematics as numpy arrays; reading BVH and
// ASF/AMC files, writing BVH.
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <algorithm>
#include <array>
#include <memory>
#include <optional>

#include "arrays.hpp"
#include "bindings.hpp"
#include "mocapdb/io/bvh.hpp"
#include "mocapdb/io/clip_file.hpp"
#include "mocapdb/motion/clip.hpp"
#include "mocapdb/motion/forward_kinematics.hpp"
#include "mocapdb/motion/local_pose_arrays.hpp"
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
        throw InvalidArgument("Clip: expected channels of shape (frames, " + std::to_string(skeleton->channel_count()) +
                              ")");
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
        joints.append(py::make_tuple(j.name, j.parent, py::make_tuple(j.offset.x(), j.offset.y(), j.offset.z()),
                                     channels, static_cast<int>(j.rotation_order),
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

/// A rig from arrays (Skeleton's constructor): channels per joint by BVH name (default: joint 0
/// Xposition Yposition Zposition Zrotation Xrotation Yrotation, other joints Zrotation Xrotation
/// Yrotation, end sites none), rotation order from the order of the rotation channels, position
/// channels replacing the offset (BVH's meaning).
SkeletonPtr skeleton_from_arrays(const std::vector<std::string>& names, const std::vector<int>& parents,
                                 const Array& offsets,
                                 const std::optional<std::vector<std::vector<std::string>>>& channels,
                                 const std::optional<std::vector<bool>>& end_sites) {
    const std::size_t n = names.size();
    if (parents.size() != n || offsets.ndim() != 2 || offsets.shape(0) != static_cast<py::ssize_t>(n) ||
        offsets.shape(1) != 3 || (channels && channels->size() != n) || (end_sites && end_sites->size() != n))
        throw InvalidArgument("Skeleton: expected " + std::to_string(n) + " parents, offsets of shape (" +
                              std::to_string(n) + ", 3) and as many channel lists and end-site flags as joint names");
    std::vector<Joint> joints(n);
    for (std::size_t j = 0; j < n; ++j) {
        Joint& joint = joints[j];
        joint.name = names[j];
        joint.parent = parents[j];
        joint.offset = Vec3(offsets.at(static_cast<py::ssize_t>(j), 0), offsets.at(static_cast<py::ssize_t>(j), 1),
                            offsets.at(static_cast<py::ssize_t>(j), 2));
        joint.end_site = end_sites && (*end_sites)[j];
        std::vector<std::string> types;
        if (channels) types = (*channels)[j];
        else if (!joint.end_site)
            types = j == 0 ? std::vector<std::string>{"Xposition", "Yposition", "Zposition",
                                                      "Zrotation", "Xrotation", "Yrotation"}
                           : std::vector<std::string>{"Zrotation", "Xrotation", "Yrotation"};
        std::vector<Axis> axes;
        for (const std::string& t : types) {
            const auto c = channel_type_from_string(t);
            if (!c)
                throw InvalidArgument("Skeleton: joint '" + joint.name + "': unknown channel '" + t +
                                      "' (expected Xposition .. Zrotation)");
            joint.channels.push_back(*c);
            if (is_rotation(*c)) axes.push_back(channel_axis(*c));
        }
        // The channels' rotation axes in order, outermost first; a missing axis comes last.
        for (Axis a : {Axis::X, Axis::Y, Axis::Z})
            if (std::find(axes.begin(), axes.end(), a) == axes.end()) axes.push_back(a);
        const auto order = euler_order_from_axes(axes[0], axes[1], axes[2]);
        if (!order)
            throw InvalidArgument("Skeleton: joint '" + joint.name +
                                  "': a rotation axis appears twice in its channels");
        joint.rotation_order = *order;
    }
    return std::make_shared<Skeleton>(std::move(joints), SourceUnits{}, Vec3::UnitZ(),
                                      PositionChannels::replace_offset);
}

/// (F, J, 4) quaternions from an (F, J, 4) quaternion or (F, J, 3, 3) matrix array.
Array rotation_quaternions(const Skeleton& s, const Array& rotations) {
    const auto j = static_cast<py::ssize_t>(s.size());
    const bool quats = rotations.ndim() == 3 && rotations.shape(1) == j && rotations.shape(2) == 4;
    const bool matrices =
        rotations.ndim() == 4 && rotations.shape(1) == j && rotations.shape(2) == 3 && rotations.shape(3) == 3;
    if (!quats && !matrices)
        throw InvalidArgument("rotations: expected (F, " + std::to_string(j) + ", 4) quaternions (w, x, y, z) or (F, " +
                              std::to_string(j) + ", 3, 3) rotation matrices");
    if (quats) return rotations;
    Array out({rotations.shape(0), j, py::ssize_t{4}});
    quaternions_of_matrices(rotations.data(), static_cast<std::size_t>(rotations.shape(0) * j), out.mutable_data());
    return out;
}

std::size_t checked_root_positions(const Array& rotations, const Array& root_positions) {
    if (root_positions.ndim() != 2 || root_positions.shape(1) != 3 || root_positions.shape(0) != rotations.shape(0))
        throw InvalidArgument("root_positions: expected shape (" + std::to_string(rotations.shape(0)) +
                              ", 3), one row per frame");
    return static_cast<std::size_t>(rotations.shape(0));
}

}  // namespace

void bind_clips(py::module_& m) {
    py::class_<Skeleton, SkeletonPtr>(
        m, "Skeleton",
        "A rig: joints (end sites included) with parents, offsets and channels."
        "\n\nExample:\n    >>> skeleton = mocapdb.read_clip('16_11.amc').skeleton\n    >>> skeleton.joint_names[:2], len(skeleton)")
        .def(py::init(&skeleton_from_arrays), py::arg("joint_names"), py::arg("parents"), py::arg("offsets"),
             py::arg("channels") = py::none(), py::arg("end_sites") = py::none(),
             "A rig from arrays, with the names of a stored skeleton's attributes: joint names, parent indices "
             "(-1 for joint 0; parents before children), (J, 3) offsets in cm, per joint its channels by BVH name "
             "(default: joint 0 Xposition Yposition Zposition Zrotation Xrotation Yrotation, the others Zrotation "
             "Xrotation Yrotation, end sites none; rotations compose in channel order) and end-site flags. Position "
             "channels replace the offset (BVH).\n\nExample:\n"
             "    >>> rig = mocapdb.Skeleton(['hips', 'knee', 'foot'], [-1, 0, 1],\n"
             "    ...                        [[0, 90, 0], [0, -45, 0], [0, -45, 0]], end_sites=[False, False, True])")
        .def(
            "fk",
            [](const Skeleton& s, const Array& rotations, const Array& root_positions) {
                const Array q = rotation_quaternions(s, rotations);
                const std::size_t frames = checked_root_positions(q, root_positions);
                Array out({frames, s.size(), std::size_t{3}});
                py::gil_scoped_release release;
                forward_kinematics_of_arrays(s, q.data(), root_positions.data(), frames, out.mutable_data());
                return out;
            },
            py::arg("local_rotations"), py::arg("root_positions"),
            "Joint positions (F, J, 3) in cm from local rotations ((F, J, 4) quaternions w x y z or (F, J, 3, 3) "
            "matrices, Clip.local_rotations) and root positions ((F, 3) cm, Clip.root_positions): joint 0 at the root "
            "position, the other joints at their offsets (Clip.joint_positions for rigs with position channels on "
            "joint 0 only).\n\nExample:\n"
            "    >>> xyz = clip.skeleton.fk(clip.local_rotations(), clip.root_positions())")
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
                for (std::size_t j = 0; j < s.size(); ++j)
                    o.row(static_cast<Eigen::Index>(j)) = s.joint(j).offset.transpose();
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
            "Clip.pose_vectors(canonical=False)."
            "\n\nExample:\n    >>> rows = clip.skeleton.channels_from_pose_vectors(clip.pose_vectors(canonical=False))")
        .def("__len__", &Skeleton::size)
        .def("__repr__",
             [](const Skeleton& s) {
                 return "<mocapdb.Skeleton " + std::to_string(s.size()) + " joints, " +
                        std::to_string(s.channel_count()) + " channels>";
             })
        .def(py::pickle(&skeleton_state, &skeleton_from_state));

    py::class_<Clip, std::shared_ptr<Clip>>(
        m, "Clip",
        "One motion: a skeleton, a frame rate and a row of channels per frame."
        "\n\nExample:\n    >>> clip = mocapdb.read_clip('16_11.amc')\n    >>> clip.channels.shape, clip.joint_positions().shape   # (F, C), (F, J, 3)")
        .def(py::init(
                 [](const SkeletonPtr& skeleton, const Array& channels, double frame_rate, const std::string& name) {
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
        .def(
            "local_rotations",
            [](const Clip& c) {
                Array out({c.frame_count(), c.skeleton->size(), std::size_t{4}});
                local_rotations_of(c, out.mutable_data());
                return out;
            },
            "(F, J, 4) unit quaternions (w, x, y, z): each joint's whole local rotation, whatever the rig's channel "
            "order or ASF axes (identity for joints without rotation channels).\n\nExample:\n"
            "    >>> q = clip.local_rotations()     # (F, J, 4)")
        .def(
            "root_positions",
            [](const Clip& c) {
                Array out({c.frame_count(), std::size_t{3}});
                root_positions_of(c, out.mutable_data());
                return out;
            },
            "(F, 3) cm: joint 0's position (its local translation) in every frame.\n\nExample:\n"
            "    >>> path = clip.root_positions()   # (F, 3)")
        .def_static(
            "from_arrays",
            [](const SkeletonPtr& skeleton, double frame_rate, const Array& rotations, const Array& root_positions,
               const std::string& name) {
                if (!skeleton) throw InvalidArgument("Clip.from_arrays: a skeleton is required");
                const Array q = rotation_quaternions(*skeleton, rotations);
                const std::size_t frames = checked_root_positions(q, root_positions);
                auto clip = std::make_shared<Clip>();
                clip->skeleton = skeleton;
                clip->frame_rate = frame_rate;
                clip->name = name;
                clip->channels = channels_from_local_rotations(*skeleton, q.data(), root_positions.data(), frames);
                validate(*clip);
                return clip;
            },
            py::arg("skeleton"), py::arg("frame_rate"), py::kw_only(), py::arg("rotations"), py::arg("root_positions"),
            py::arg("name") = "",
            "A clip of the skeleton from local rotations ((F, J, 4) quaternions w x y z or (F, J, 3, 3) matrices) and "
            "root positions ((F, 3) cm): the channel values giving them (Euler angles continuous in time; a rotation "
            "a joint's channels cannot express loses its missing axes), the inverse of local_rotations() and "
            "root_positions().\n\nExample:\n"
            "    >>> copy = mocapdb.Clip.from_arrays(clip.skeleton, clip.frame_rate,\n"
            "    ...                                 rotations=clip.local_rotations(), root_positions=clip.root_positions())\n"
            "    >>> mocapdb.write_bvh(copy, 'copy.bvh')")
        .def(
            "joint_positions", &joint_positions_array,
            "Global joint positions (F, J, 3) in cm by forward kinematics, every joint and end site "
            "(Skeleton.joint_names order); the GIL is released."
            "\n\nExample:\n    >>> xyz = clip.joint_positions()   # (F, J, 3)\n    >>> head = xyz[:, clip.skeleton.joint_names.index('head')]")
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
            "the origin facing +Z (else the world frame)."
            "\n\nExample:\n    >>> poses = clip.pose_vectors()      # (F, D)")
        .def(
            "slice", [](const Clip& c, std::size_t begin, std::size_t end) { return slice(c, begin, end); },
            py::arg("begin"), py::arg("end"),
            "Frames [begin, end) as a clip of their own."
            "\n\nExample:\n    >>> first_second = clip.slice(0, 120)")
        .def("write_bvh", &write_bvh_file, py::arg("path"), py::arg("precision") = 9,
             "Writes the clip as BVH (atomically; an existing file is replaced). precision: significant digits "
             "(17 is lossless)."
             "\n\nExample:\n    >>> clip.write_bvh('walk.bvh', precision=17)")
        .def("__len__", &Clip::frame_count)
        .def("__repr__",
             [](const Clip& c) {
                 return "<mocapdb.Clip '" + c.name + "' " + std::to_string(c.frame_count()) + " frames at " +
                        std::to_string(c.frame_rate) + " Hz>";
             })
        .def(py::pickle(
            [](const Clip& c) {
                return py::make_tuple(std::const_pointer_cast<Skeleton>(c.skeleton), copy_rows(c.channels),
                                      c.frame_rate, c.name);
            },
            [](const py::tuple& t) {
                if (t.size() != 4) throw InvalidArgument("Clip: not a pickled clip's state");
                return std::make_shared<Clip>(make_clip(t[0].cast<SkeletonPtr>(), t[1].cast<Array>(),
                                                        t[2].cast<double>(), t[3].cast<std::string>()));
            }));

    m.def(
        "read_clip",
        [](const std::filesystem::path& path, std::optional<std::filesystem::path> asf,
           std::optional<double> frame_rate, bool strict, const std::string& bvh_positions) {
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
        "or 'add_to_offset'."
        "\n\nExample:\n    >>> clip = mocapdb.read_clip('16_11.amc')          # 16.asf beside it\n    >>> clip = mocapdb.read_clip('walk.bvh', strict=True)");
    m.def("write_bvh", &write_bvh_file, py::arg("clip"), py::arg("path"), py::arg("precision") = 9,
          "Writes a clip as BVH (atomically; an existing file is replaced)."
          "\n\nExample:\n    >>> mocapdb.write_bvh(mocapdb.read_clip('16_11.amc'), '16_11.bvh')");
}

}  // namespace mocapdb::python
