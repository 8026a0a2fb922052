// AMC (Acclaim motion) text -> Clip, against a skeleton read from the matching ASF; and the CMU
// file-name rule that pairs them. Policies (units, frame numbering, truncation) are in asf_amc.hpp.
#include "mocapdb/io/asf_amc.hpp"

#include <charconv>
#include <cmath>
#include <limits>
#include <unordered_map>
#include <vector>

#include "asf_text.hpp"
#include "mocapdb/core/error.hpp"
#include "mocapdb/io/frame_rate.hpp"
#include "mocapdb/io/text_file.hpp"
#include "text_scanner.hpp"

namespace mocapdb {
namespace {

using detail::iequals;
using detail::quoted;
using detail::TextScanner;

constexpr std::size_t kNever = std::numeric_limits<std::size_t>::max();

/// Where one AMC bone line goes in a frame row.
struct BoneSlot {
    std::size_t joint = 0;
    std::size_t first_column = 0;
    std::size_t count = 0;
    std::size_t seen_in_frame = kNever;  ///< ordinal of the last frame that had this bone
    std::size_t seen_line = 0;
};

bool is_digit(char c) { return c >= '0' && c <= '9'; }

class AmcParser {
public:
    AmcParser(std::string_view text, const std::string& source_name, const Skeleton& skeleton,
              const AmcReadOptions& options, Warnings* warnings)
        : text_(detail::blank_comments(text)),
          s_(text_, source_name),
          skeleton_(skeleton),
          options_(options),
          warnings_(warnings),
          channels_(skeleton.channel_count()) {
        // One slot per joint that is an ASF bone (end sites are not), looked up by name once per line.
        for (std::size_t j = 0; j < skeleton.size(); ++j) {
            const Joint& joint = skeleton.joint(j);
            if (joint.end_site) continue;
            BoneSlot slot;
            slot.joint = j;
            slot.first_column = skeleton.first_channel(j);
            slot.count = joint.channels.size();
            if (slot.count > 0) ++required_;
            index_.emplace(std::string_view(joint.name), slots_.size());
            slots_.push_back(slot);
        }
    }

    FrameMatrix run() {
        parse_header();
        parse_frames();
        if (frames_ == 0)
            throw ParseError(s_.source_name(), 0, 0,
                             "no complete motion frames (expected a frame number line followed by one line per bone)");
        return Eigen::Map<const FrameMatrix>(data_.data(), static_cast<Eigen::Index>(frames_),
                                             static_cast<Eigen::Index>(channels_));
    }

private:
    std::string text_;  // comment-free copy the scanner reads
    TextScanner s_;
    const Skeleton& skeleton_;
    const AmcReadOptions& options_;
    Warnings* warnings_;
    std::size_t channels_;
    std::vector<BoneSlot> slots_;
    std::unordered_map<std::string_view, std::size_t> index_;
    std::size_t required_ = 0;  // bones with at least one value, each needed once per frame

    std::vector<double> data_;
    std::vector<double> scale_;  // per column: file units -> cm or radians
    std::size_t frames_ = 0;     // frames stored in data_
    bool in_frame_ = false;
    long long frame_number_ = 0;
    std::size_t frame_line_ = 0;
    std::size_t seen_in_frame_ = 0;  // bones with values seen in the current frame

    void warn_or_fail(std::size_t line, const std::string& message) {
        if (options_.strict) throw ParseError(s_.source_name(), line, 0, message);
        if (warnings_) warnings_->push_back(Warning{s_.source_name(), line, message});
    }

    void parse_header() {
        const bool asf_degrees = skeleton_.source_units().degrees;
        bool degrees = asf_degrees;
        while (!s_.at_end() && s_.peek_token().front() == ':') {
            const std::string_view kw = s_.token();
            const std::size_t line = s_.token_line();
            if (iequals(kw, ":DEGREES") || iequals(kw, ":RADIANS")) {
                degrees = iequals(kw, ":DEGREES");
                if (degrees != asf_degrees)
                    warn_or_fail(line, std::string("the AMC says ") + (degrees ? ":DEGREES" : ":RADIANS") +
                                           " but its ASF's ':units angle' is " + (asf_degrees ? "deg" : "rad") +
                                           "; the AMC's unit is used for its values");
            } else if (!iequals(kw, ":FULLY-SPECIFIED")) {
                warn_or_fail(line, "unknown AMC header keyword " + quoted(kw) + " (ignored)");
            }
            if (!s_.at_line_end()) {
                const std::string_view extra = s_.token_on_line();
                s_.fail_at_token("unexpected " + quoted(extra) + " after " + quoted(kw));
            }
        }
        const double cm = skeleton_.source_units().cm_per_unit;
        const double angle = degrees ? kPi / 180.0 : 1.0;
        scale_.resize(channels_);
        for (std::size_t j = 0; j < skeleton_.size(); ++j) {
            const auto& ch = skeleton_.joint(j).channels;
            for (std::size_t k = 0; k < ch.size(); ++k)
                scale_[skeleton_.first_channel(j) + k] = is_rotation(ch[k]) ? angle : cm;
        }
    }

    std::string frame_label() const { return "frame " + std::to_string(frame_number_); }

    // The first required bone missing from the current frame, and how many more are missing.
    std::pair<const BoneSlot*, std::size_t> missing_bones() const {
        const BoneSlot* first = nullptr;
        std::size_t more = 0;
        for (const BoneSlot& b : slots_) {
            if (b.count == 0 || b.seen_in_frame == frames_) continue;
            if (first == nullptr) first = &b;
            else ++more;
        }
        return {first, more};
    }

    std::string missing_message() const {
        const auto [first, more] = missing_bones();
        std::string m = frame_label() + " has no line for bone '" + skeleton_.joint(first->joint).name + "'";
        if (more > 0) m += " (nor for " + std::to_string(more) + " other bone" + (more > 1 ? "s" : "") + ")";
        return m;
    }

    /// Ends the current frame. An incomplete frame is an error, except the file's last frame in
    /// non-strict mode, which is dropped with a warning (a truncated file keeps its complete frames).
    void close_frame(bool last_in_file) {
        if (!in_frame_) return;
        in_frame_ = false;
        if (seen_in_frame_ == required_) {
            ++frames_;
            return;
        }
        if (!last_in_file) throw ParseError(s_.source_name(), frame_line_, 0, missing_message());
        const std::string m = missing_message() + ": the file ends inside " + frame_label();
        if (options_.strict) throw ParseError(s_.source_name(), frame_line_, 0, m);
        warn_or_fail(frame_line_, m + "; the incomplete frame was dropped");
        data_.resize(frames_ * channels_);
    }

    void start_frame(std::string_view t) {
        const bool first = frames_ == 0 && !in_frame_;
        close_frame(false);
        long long number = 0;
        const auto [ptr, ec] = std::from_chars(t.data(), t.data() + t.size(), number);
        if (ec != std::errc() || ptr != t.data() + t.size())
            s_.fail_at_token("expected a frame number (a non-negative integer), found " + quoted(t));
        // Unsigned so that a frame number at the top of the range cannot overflow.
        const unsigned long long next = static_cast<unsigned long long>(frame_number_) + 1;
        if (!first && static_cast<unsigned long long>(number) != next)
            warn_or_fail(s_.token_line(), "frame number " + std::to_string(number) + " follows frame " +
                                              std::to_string(frame_number_) + " (expected " + std::to_string(next) +
                                              "); frames are kept in file order");
        frame_number_ = number;
        frame_line_ = s_.token_line();
        in_frame_ = true;
        seen_in_frame_ = 0;
        data_.resize((frames_ + 1) * channels_, 0.0);
        if (!s_.at_line_end()) {
            const std::string_view extra = s_.token_on_line();
            s_.fail_at_token("unexpected " + quoted(extra) +
                             " after the frame number (bone values go on the "
                             "following lines)");
        }
    }

    /// Returns false when the file ended inside this line's values and the frame was dropped.
    bool bone_line(std::string_view name) {
        if (!in_frame_) s_.fail_at_token("expected a frame number before the bone values, found " + quoted(name));
        const auto it = index_.find(name);
        if (it == index_.end())
            s_.fail_at_token("unknown bone " + quoted(name) + " in " + frame_label() + " (not a bone of the skeleton)");
        BoneSlot& slot = slots_[it->second];
        if (slot.seen_in_frame == frames_)
            s_.fail_at_token("bone " + quoted(name) + " appears twice in " + frame_label() + " (first at line " +
                             std::to_string(slot.seen_line) + ")");
        slot.seen_in_frame = frames_;
        slot.seen_line = s_.token_line();
        if (slot.count > 0) ++seen_in_frame_;

        double* row = data_.data() + frames_ * channels_ + slot.first_column;
        const double* scale = scale_.data() + slot.first_column;
        std::size_t k = 0;
        try {
            for (; k < slot.count; ++k) {
                const std::string_view v = s_.token_on_line();
                if (v.empty()) break;
                row[k] = s_.to_number(v, "bone value") * scale[k];
            }
        } catch (const ParseError& e) {
            throw ParseError(e.file(), e.line(), e.column(),
                             e.message() + " (bone '" + std::string(name) + "', " + frame_label() + ")");
        }
        if (k < slot.count) return short_line(name, slot.count, k);
        if (!s_.at_line_end()) {
            std::size_t found = slot.count;
            const std::string_view first_extra = s_.token_on_line();
            const std::size_t line = s_.token_line(), column = s_.column() - first_extra.size();
            for (++found; !s_.token_on_line().empty();) ++found;
            throw ParseError(s_.source_name(), line, column,
                             "expected " + std::to_string(slot.count) + " values for bone '" + std::string(name) +
                                 "', found " + std::to_string(found) + " (" + frame_label() + ")");
        }
        return true;
    }

    bool short_line(std::string_view name, std::size_t expected, std::size_t found) {
        const std::size_t line = s_.line(), column = s_.column();
        std::string m = "expected " + std::to_string(expected) + " values for bone '" + std::string(name) +
                        "', found " + std::to_string(found) + " (" + frame_label() + ")";
        if (!s_.at_end()) throw ParseError(s_.source_name(), line, column, m);
        // The file stops inside this line: the truncation policy of close_frame applies.
        m += ": the file ends inside " + frame_label();
        if (options_.strict) throw ParseError(s_.source_name(), line, column, m);
        warn_or_fail(line, m + "; the incomplete frame was dropped");
        in_frame_ = false;
        data_.resize(frames_ * channels_);
        return false;
    }

    void parse_frames() {
        while (!s_.at_end()) {
            const std::string_view t = s_.token_on_line();
            if (is_digit(t.front())) {
                start_frame(t);
            } else if (!bone_line(t)) {
                return;
            }
        }
        close_frame(true);
    }
};

}  // namespace

Clip parse_amc(std::string_view text, const std::string& source_name, std::shared_ptr<const Skeleton> skeleton,
               const AmcReadOptions& options, Warnings* out_warnings) {
    if (!skeleton) throw InvalidArgument("parse_amc: a skeleton is required");
    check_frame_rate(options.frame_rate, "parse_amc");
    Clip clip;
    clip.channels = AmcParser(text, source_name, *skeleton, options, out_warnings).run();
    clip.skeleton = std::move(skeleton);
    clip.frame_rate = options.frame_rate;
    clip.name = std::filesystem::path(source_name).stem().string();
    return clip;
}

Clip read_amc(const std::filesystem::path& path, std::shared_ptr<const Skeleton> skeleton,
              const AmcReadOptions& options, Warnings* out_warnings) {
    if (!skeleton) throw InvalidArgument("read_amc: a skeleton is required");
    return parse_amc(read_text_file(path), path.string(), std::move(skeleton), options, out_warnings);
}

std::optional<std::filesystem::path> find_asf_for_amc(const std::filesystem::path& amc_path) {
    const std::string stem = amc_path.stem().string();
    const std::size_t underscore = stem.find('_');
    if (underscore == std::string::npos || underscore == 0) return std::nullopt;
    const std::string subject = stem.substr(0, underscore);
    for (const char* ext : {".asf", ".ASF"}) {
        const std::filesystem::path candidate = amc_path.parent_path() / (subject + ext);
        std::error_code ec;
        if (std::filesystem::is_regular_file(candidate, ec)) return candidate;
    }
    return std::nullopt;
}

}  // namespace mocapdb
