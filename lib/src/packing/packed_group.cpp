#include "mocapdb/packing/packed_group.hpp"

#include <chrono>
#include <cmath>
#include <cstring>
#include <optional>

#include <zdict.h>
#include <zstd.h>

#include "../core/byte_stream.hpp"
#include "pack_stages.hpp"
#include "runtime_encoder_body.hpp"
#include "runtime_layout.hpp"
#include "runtime_pose.hpp"

namespace mocapdb::packing {
namespace {

using detail::GroupModel;
using detail::step_of;
using detail::WindowResult;

void check_options(const PackOptions& o) {
    if (!(o.max_error_cm > 0) || !std::isfinite(o.max_error_cm))
        throw InvalidArgument("pack: max error must be a finite number > 0 cm, got " + std::to_string(o.max_error_cm));
    if (o.window < 2 || o.window > 256)
        throw InvalidArgument("pack: window must be 2..256 frames, got " + std::to_string(o.window));
    if (!(o.rounding >= 0.1 && o.rounding <= 0.5))
        throw InvalidArgument("pack: rounding must be in [0.1, 0.5], got " + std::to_string(o.rounding));
    if (o.threads < 1) throw InvalidArgument("pack: threads must be >= 1");
    if (o.trim_tail < 0) throw InvalidArgument("pack: trim_tail must be >= 0");
}

void check_clips(const std::vector<const Clip*>& clips) {
    for (const Clip* c : clips) {
        if (c == nullptr) throw InvalidArgument("pack: null clip");
        validate(*c);
        if (c->frame_count() == 0) throw InvalidArgument("pack: clip '" + c->name + "' has no frames");
        if (c->frame_rate != clips.front()->frame_rate ||
            !detail::same_topology(*c->skeleton, *clips.front()->skeleton))
            throw InvalidArgument("pack: clip '" + c->name + "' has another topology or frame rate than '" +
                                  clips.front()->name + "' (use group_clips)");
    }
}

double seconds_since(std::chrono::steady_clock::time_point started) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
}

/// Every k-th clip (k = ceil(clips / 8)), each cut to its first 4000 frames.
std::vector<Clip> bases_sample(const std::vector<const Clip*>& clips) {
    const std::size_t every = (clips.size() + 7) / 8;
    std::vector<Clip> sample;
    for (std::size_t i = 0; i < clips.size(); i += every) {
        sample.push_back(clips[i]->frame_count() > 4000 ? slice(*clips[i], 0, 4000) : *clips[i]);
        sample.back().name = clips[i]->name;
    }
    return sample;
}

/// Options with Auto bases: each candidate packed on a sample; the group's bytes estimated as header
/// plus payload and tables scaled by frames; the options with the fewest.
PackOptions choose_bases(const std::vector<const Clip*>& clips, const PackOptions& options) {
    const std::vector<Clip> sample = bases_sample(clips);
    std::size_t all_frames = 0, sample_frames = 0;
    for (const Clip* c : clips) all_frames += c->frame_count();
    std::vector<const Clip*> sample_ptrs;
    for (const Clip& c : sample) {
        sample_ptrs.push_back(&c);
        sample_frames += c.frame_count();
    }
    std::vector<TimeBasis> times{options.time_basis};
    if (options.time_basis == TimeBasis::Auto) times = {TimeBasis::Learned, TimeBasis::Cosine};
    std::vector<DofBasis> dofs{options.dof_basis};
    if (options.dof_basis == DofBasis::Auto) dofs = {DofBasis::Learned, DofBasis::Identity};
    PackOptions best = options;
    double best_bytes = 0.0;
    bool first = true;
    for (TimeBasis tb : times)
        for (DofBasis db : dofs) {
            PackOptions trial = options;
            trial.time_basis = tb;
            trial.dof_basis = db;
            trial.compare_zstd = false;
            const PackStats s = pack_group(sample_ptrs, trial).stats;
            const double estimate = static_cast<double>(s.header_bytes) +
                                    static_cast<double>(s.payload_bytes + s.table_bytes) *
                                        static_cast<double>(all_frames) / static_cast<double>(sample_frames);
            if (first || estimate < best_bytes) {
                best = trial;
                best_bytes = estimate;
                first = false;
            }
        }
    best.compare_zstd = options.compare_zstd;
    return best;
}

/// zstd's sizes for the windows' coefficients (see PackStats::zstd_*).
void measure_zstd(const std::vector<WindowResult>& results, PackStats& out) {
    std::vector<std::uint8_t> all;
    std::vector<std::size_t> sizes;
    for (const WindowResult& r : results) {
        const std::size_t before = all.size();
        all.push_back(r.step);
        for (std::int32_t v : r.q) byte_stream::put_varint(all, byte_stream::zigzag(v));
        sizes.push_back(all.size() - before);
    }
    const int level = 19;
    std::vector<std::uint8_t> buffer(ZSTD_compressBound(all.size()));
    out.zstd_stream_bytes = ZSTD_compress(buffer.data(), buffer.size(), all.data(), all.size(), level);
    std::vector<std::uint8_t> dictionary(16384);
    const std::size_t dict_size = ZDICT_trainFromBuffer(dictionary.data(), dictionary.size(), all.data(), sizes.data(),
                                                        static_cast<unsigned>(sizes.size()));
    const bool have_dict = !ZDICT_isError(dict_size);
    ZSTD_CCtx* cctx = ZSTD_createCCtx();
    ZSTD_CDict* cdict = have_dict ? ZSTD_createCDict(dictionary.data(), dict_size, level) : nullptr;
    out.zstd_window_bytes = 0;
    out.zstd_dictionary_bytes = have_dict ? dict_size : 0;
    std::size_t offset = 0;
    for (std::size_t size : sizes) {
        const std::size_t plain =
            ZSTD_compressCCtx(cctx, buffer.data(), buffer.size(), all.data() + offset, size, level);
        out.zstd_window_bytes += plain;
        out.zstd_dictionary_bytes +=
            cdict ? ZSTD_compress_usingCDict(cctx, buffer.data(), buffer.size(), all.data() + offset, size, cdict)
                  : plain;
        offset += size;
    }
    ZSTD_freeCDict(cdict);
    ZSTD_freeCCtx(cctx);
}

/// Pass 2: every window entropy-coded from the trained contexts (raw windows: their rows as bytes);
/// m.windows gets their steps and sizes, `results` is emptied.
std::vector<std::vector<std::uint8_t>> encode_windows(GroupModel& m, std::vector<WindowResult>& results) {
    std::vector<std::vector<std::uint8_t>> payloads(results.size());
    m.windows.resize(results.size());
    std::vector<std::uint8_t> classes;
    for (std::size_t w = 0; w < results.size(); ++w) {
        if (results[w].step == detail::kRawStep) {
            payloads[w].resize(results[w].raw.size() * sizeof(double));
            std::memcpy(payloads[w].data(), results[w].raw.data(), payloads[w].size());
        } else {
            position_classes(m.levels, step_of(results[w].step), classes);
            payloads[w] = encode_coefficients(results[w].q, classes, m.grid(), m.contexts);
        }
        m.windows[w].step = results[w].step;
        m.windows[w].size = static_cast<std::uint32_t>(payloads[w].size());
        results[w].q = {};
        results[w].raw = {};
    }
    return payloads;
}

/// The group's bytes (header and tables, then the payloads) into result, with the parts and the
/// payload bytes; returns the bytes before the payload.
std::size_t assemble(const GroupModel& m, const std::vector<std::vector<std::uint8_t>>& payloads, PackedGroup& result) {
    m.write_header(result.bytes, &result.stats.parts);
    const std::size_t before_payload = result.bytes.size();
    std::uint64_t coded_bytes = 0, raw_bytes = 0;
    for (std::size_t w = 0; w < payloads.size(); ++w) {
        result.stats.payload_bytes += payloads[w].size();
        (m.windows[w].step == detail::kRawStep ? raw_bytes : coded_bytes) += payloads[w].size();
    }
    add_part(result.stats.parts, "payload", coded_bytes);
    add_part(result.stats.parts, "raw_windows", raw_bytes);
    result.bytes.reserve(before_payload + result.stats.payload_bytes);
    for (const auto& p : payloads) result.bytes.insert(result.bytes.end(), p.begin(), p.end());
    return before_payload;
}

/// The sizes and counts of a packed group (the table's bytes as write_header's varints).
void count_sizes(const std::vector<const Clip*>& clips, const GroupModel& m, std::size_t before_payload,
                 PackStats& st) {
    st.clips = clips.size();
    for (const Clip* c : clips) st.frames += c->frame_count();
    st.windows = m.windows.size();
    st.channels = clips.front()->skeleton->channel_count();
    std::size_t table = 0;
    for (const auto& c : m.clips) table += 12 + (c.frames < 128 ? 1 : c.frames < 16384 ? 2 : 3) + 1;
    for (const auto& w : m.windows) table += 1 + (w.size < 128 ? 1 : w.size < 16384 ? 2 : 3);
    st.table_bytes = table;
    st.header_bytes = before_payload - table;
}

/// The Runtime format (format 4): the model's layout, active dofs and dof basis as Archive fits them
/// (no window search), its header read back (what the decoder will see), the body encoded from that,
/// then header (with the body's checksum) and body. Nothing when the group has more active dofs than
/// the runtime format holds.
std::optional<PackedGroup> pack_runtime(const std::vector<const Clip*>& clips, const PackOptions& options,
                                        const ProgressCallback& progress) {
    if (options.runtime_window != 0 && options.runtime_window != 8 && options.runtime_window != 16)
        throw InvalidArgument("pack: runtime window must be 0 (choose), 8 or 16 frames, got " +
                              std::to_string(options.runtime_window));
    PackedGroup result;
    result.stats.format = PackFormat::Runtime;
    result.stats.dof_basis = options.dof_basis == DofBasis::Identity ? DofBasis::Identity : DofBasis::Learned;
    GroupModel m;
    m.runtime = true;
    if (clips.empty()) {
        m.write_header(result.bytes, &result.stats.parts);
        result.stats.bytes = result.stats.header_bytes = result.bytes.size();
        return result;
    }
    PackOptions fit = options;
    fit.dof_basis = result.stats.dof_basis;
    fit.time_basis = TimeBasis::Learned;
    const std::uint64_t window_total = detail::layout_group(clips, fit.window, m);
    detail::PackRun run(clips, fit, progress, window_total);
    detail::find_active_dofs(run, m);
    if (m.active.size() > static_cast<std::size_t>(detail::kRuntimeMaxDofs)) return std::nullopt;
    detail::fit_bases(run, m);
    std::vector<std::uint8_t> header;
    m.write_header(header);
    GroupModel seen;  // the decoder's view: float32 skeletons, canonicalizations and basis as stored
    seen.read_header(header.data(), header.size());
    RuntimeOptions ro;
    ro.max_error_cm = options.max_error_cm;
    ro.window = options.runtime_window;
    ro.rounding = options.rounding;
    ro.threads = options.threads;
    // Progress: pass 0 counted each clip's windows (W of fit.window) once; the encode counts them again.
    RuntimeBody body = detail::encode_runtime_body(seen, clips, ro, [&](std::size_t i, int passes) {
        const auto windows = detail::window_count(clips[i]->frame_count(), fit.window);
        run.done(*clips[i], static_cast<int>(windows / static_cast<std::uint64_t>(passes)));  // never past the total
    });
    m.body_crc = detail::runtime_body_crc(body.bytes.data(), body.bytes.size());
    m.write_header(result.bytes, &result.stats.parts);
    PackStats& st = result.stats;
    for (const BytePart& p : st.parts)
        if (p.name == "clip_table") st.table_bytes = p.bytes;
    st.header_bytes = result.bytes.size() - st.table_bytes;
    add_part(st.parts, "body_header", body.stats.header_bytes);
    add_part(st.parts, "code_tables", body.stats.side_bytes);
    add_part(st.parts, "offsets", body.stats.offset_bytes);
    add_part(st.parts, "payload", body.stats.entry_bytes);
    add_part(st.parts, "slack", body.stats.slack_bytes);
    st.payload_bytes = body.bytes.size();
    result.bytes.insert(result.bytes.end(), body.bytes.begin(), body.bytes.end());
    st.bytes = result.bytes.size();
    st.clips = clips.size();
    for (const Clip* c : clips) st.frames += c->frame_count();
    st.channels = clips.front()->skeleton->channel_count();
    st.runtime_window = body.stats.window;
    for (const Clip* c : clips) st.windows += detail::runtime_entry_count(c->frame_count(), body.stats.window) - 1;
    st.error.max_cm = body.stats.max_error_cm;
    for (const Clip* c : clips) st.error.positions += c->frame_count() * c->skeleton->size();
    if (progress) progress(Progress{window_total * 2, window_total * 2, {}});
    return result;
}

}  // namespace

std::vector<std::vector<std::size_t>> group_clips(const std::vector<const Clip*>& clips) {
    std::vector<std::vector<std::size_t>> groups;
    std::vector<const Clip*> firsts;
    for (std::size_t i = 0; i < clips.size(); ++i) {
        const Clip& c = *clips[i];
        std::size_t g = 0;
        for (; g < firsts.size(); ++g)
            if (firsts[g]->frame_rate == c.frame_rate && detail::same_topology(*firsts[g]->skeleton, *c.skeleton))
                break;
        if (g == firsts.size()) {
            firsts.push_back(&c);
            groups.emplace_back();
        }
        groups[g].push_back(i);
    }
    return groups;
}

PackedGroup pack_group(const std::vector<const Clip*>& clips, const PackOptions& options,
                       const ProgressCallback& progress) {
    check_options(options);
    const auto started = std::chrono::steady_clock::now();
    check_clips(clips);
    if (options.format == PackFormat::Runtime) {
        std::optional<PackedGroup> runtime;
        try {
            runtime = pack_runtime(clips, options, progress);
        } catch (const PackingFailed&) {
            // A frame no step of the runtime format brings within E (Archive stores such windows as
            // their source rows).
        }
        if (runtime) {
            runtime->stats.encode_seconds = seconds_since(started);
            return std::move(*runtime);
        }
        PackOptions archive = options;  // more active dofs than the runtime format holds, or E too fine for it
        archive.format = PackFormat::Archive;
        PackedGroup packed = pack_group(clips, archive, progress);
        packed.stats.encode_seconds = seconds_since(started);
        return packed;
    }
    if (!clips.empty() && (options.time_basis == TimeBasis::Auto || options.dof_basis == DofBasis::Auto)) {
        PackedGroup chosen = pack_group(clips, choose_bases(clips, options), progress);
        chosen.stats.encode_seconds = seconds_since(started);
        return chosen;
    }
    PackedGroup result;
    GroupModel m;
    result.stats.time_basis = options.time_basis == TimeBasis::Auto ? TimeBasis::Learned : options.time_basis;
    result.stats.dof_basis = options.dof_basis == DofBasis::Auto ? DofBasis::Learned : options.dof_basis;
    if (clips.empty()) {
        m.write_header(result.bytes, &result.stats.parts);
        result.stats.bytes = result.stats.header_bytes = result.bytes.size();
        return result;
    }
    const std::uint64_t window_total = detail::layout_group(clips, options.window, m);
    detail::PackRun run(clips, options, progress, window_total);
    detail::find_active_dofs(run, m);
    detail::fit_bases(run, m);
    detail::SearchTotals totals(options.max_error_cm);
    std::vector<WindowResult> results = detail::quantize_windows(run, m, window_total, totals);
    result.stats.probes = totals.probes;
    result.stats.raw_windows = totals.raw_windows;
    m.contexts = totals.counts.to_contexts();
    if (options.compare_zstd) measure_zstd(results, result.stats);

    const std::size_t before_payload = assemble(m, encode_windows(m, results), result);
    count_sizes(clips, m, before_payload, result.stats);
    result.stats.bytes = result.bytes.size();
    result.stats.error = totals.errors.stats();
    result.stats.encode_seconds = seconds_since(started);
    return result;
}

}  // namespace mocapdb::packing
