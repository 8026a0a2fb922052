#include "mocapdb_serve/api.hpp"

#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <mutex>
#include <sstream>
#include <vector>

#include "embedded_assets.hpp"
#include "mocapdb/core/error.hpp"
#include "mocapdb/io/bvh.hpp"
#include "mocapdb/io/gltf_writer.hpp"
#include "mocapdb/store/database.hpp"
#include "mocapdb/store/not_found_error.hpp"
#include "mocapdb/workflow/clip_view.hpp"
#include "mocapdb/workflow/demo_queries.hpp"
#include "mocapdb/workflow/load_model.hpp"
#include "mocapdb_json/view_json.hpp"

namespace mocapdb::serve {
// Named, not anonymous: Api::State (external linkage) holds these types.
namespace api_parts {

/// A request the client can fix (400).
struct BadRequest : std::runtime_error {
    using std::runtime_error::runtime_error;
};

/// A path or name that is not there (404).
struct Missing : std::runtime_error {
    using std::runtime_error::runtime_error;
};

Reply json_reply(const json::JsonWriter& j, int status = 200) { return {status, "application/json", j.str(), {}}; }

Reply error_reply(int status, const std::string& message) {
    json::JsonWriter j;
    json::write_error(j, message);
    return json_reply(j, status);
}

/// Binary motion reply: u32 (little-endian) length of the JSON header, the header, zero bytes up to a
/// multiple of 4, then float32 values (little-endian; the header says what they are).
Reply binary_reply(const json::JsonWriter& header, const std::vector<const std::vector<float>*>& blocks) {
    std::string h = header.str();
    const std::uint32_t n = static_cast<std::uint32_t>(h.size());
    std::string body;
    body.reserve(4 + h.size() + 4);
    for (int k = 0; k < 4; ++k) body.push_back(static_cast<char>((n >> (8 * k)) & 0xFF));
    body += h;
    while (body.size() % 4) body.push_back('\0');
    for (const auto* b : blocks) {
        const std::size_t at = body.size();
        body.resize(at + b->size() * sizeof(float));
        std::memcpy(&body[at], b->data(), b->size() * sizeof(float));  // x86-64 and ARM64: little-endian
    }
    return {200, "application/octet-stream", std::move(body), {}};
}

const std::string& required(const Query& q, const char* key) {
    const auto it = q.find(key);
    if (it == q.end() || it->second.empty()) throw BadRequest(std::string("missing query parameter '") + key + "'");
    return it->second;
}

std::size_t count_parameter(const Query& q, const char* key, std::size_t fallback, std::size_t max) {
    const auto it = q.find(key);
    if (it == q.end()) return fallback;
    const std::string& s = it->second;
    char* end = nullptr;
    errno = 0;
    const unsigned long long v = std::strtoull(s.c_str(), &end, 10);
    if (s.empty() || s[0] == '-' || *end != '\0' || errno == ERANGE || v > max)
        throw BadRequest(std::string("query parameter '") + key + "': expected a whole number from 0 to " +
                         std::to_string(max) + ", got '" + s + "'");
    return static_cast<std::size_t>(v);
}

VecX number_list(const std::string& text, const char* key) {
    std::vector<double> v;
    std::size_t at = 0;
    while (at <= text.size()) {
        const std::size_t comma = std::min(text.find(',', at), text.size());
        const std::string item = text.substr(at, comma - at);
        char* end = nullptr;
        const double x = std::strtod(item.c_str(), &end);
        if (item.empty() || *end != '\0' || !std::isfinite(x))
            throw BadRequest(std::string("query parameter '") + key + "': '" + item +
                             "' is not a finite number (expected values separated by commas)");
        v.push_back(x);
        if (v.size() > 64) throw BadRequest(std::string("query parameter '") + key + "': more than 64 values");
        at = comma + 1;
    }
    return Eigen::Map<const VecX>(v.data(), static_cast<Eigen::Index>(v.size()));
}

std::string file_text(const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in)
        throw IoError(
            path.string() +
            ": cannot read the page's three.js file (Debian package libjs-three; scripts/setup.sh installs it)");
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}

enum class Download { None, Bvh, Glb };

/// A motion as a file to download.
Reply download(const Clip& clip, Download as, const std::string& stem) {
    std::ostringstream s;
    if (as == Download::Glb) {
        write_gltf(s, clip, GltfContainer::Glb);
        return {200, "model/gltf-binary", s.str(), stem + ".glb"};
    }
    write_bvh(s, clip);
    return {200, "text/plain; charset=utf-8", s.str(), stem + ".bvh"};
}

struct LoadedModel {
    std::filesystem::file_time_type stamp;
    MotionSet set;
    std::shared_ptr<const synthesis::SynthesisModel> model;
};

}  // namespace api_parts
using namespace api_parts;

struct Api::State {
    ServeOptions options;
    std::map<std::string, Reply> files;  ///< the page's own files by path
    std::mutex db;                       ///< HDF5's serial build: one reader at a time
    std::mutex models_mutex;
    std::map<std::string, LoadedModel> models;

    Reply route(const std::string& path, const Query& q);
    Reply clips();
    Reply clip(const Query& q);
    Reply packed(const Query& q);
    Reply sets();
    Reply synth(const Query& q, Download as);
    Reply reliability(const Query& q);
    Reply clip_file(const Query& q, Download as);
    LoadedModel model(const std::string& set);
    std::pair<std::size_t, std::size_t> range(const Query& q) const;
};

Api::Api(ServeOptions options) : state_(std::make_unique<State>()) {
    state_->options = std::move(options);
    for (const EmbeddedAsset& a : embedded_assets())
        state_->files[std::string("/") + a.name] = Reply{200, a.content_type, std::string(a.data, a.size), {}};
    state_->files["/"] = state_->files.at("/index.html");
    const auto& dir = state_->options.three_dir;
    state_->files["/three.min.js"] = {200, "text/javascript", file_text(dir / "build" / "three.min.js"), {}};
    state_->files["/OrbitControls.js"] = {
        200, "text/javascript", file_text(dir / "examples" / "js" / "controls" / "OrbitControls.js"), {}};
    Database check(state_->options.database);  // fails now, not at the first request
}

Api::~Api() = default;

Reply Api::get(const std::string& path, const Query& query) const {
    try {
        return state_->route(path, query);
    } catch (const BadRequest& e) {
        return error_reply(400, e.what());
    } catch (const Missing& e) {
        return error_reply(404, e.what());
    } catch (const NotFoundError& e) {
        return error_reply(404, e.what());
    } catch (const InvalidArgument& e) {
        return error_reply(400, e.what());
    } catch (const ParseError& e) {
        return error_reply(400, e.what());
    } catch (const std::exception& e) {
        return error_reply(500, e.what());
    }
}

Reply Api::State::route(const std::string& path, const Query& q) {
    if (path == "/api/clips") return clips();
    if (path == "/api/clip") return clip(q);
    if (path == "/api/packed") return packed(q);
    if (path == "/api/sets") return sets();
    if (path == "/api/synth") return synth(q, Download::None);
    if (path == "/api/reliability") return reliability(q);
    if (path == "/api/clip.bvh") return clip_file(q, Download::Bvh);
    if (path == "/api/clip.glb") return clip_file(q, Download::Glb);
    if (path == "/api/synth.bvh") return synth(q, Download::Bvh);
    if (path == "/api/synth.glb") return synth(q, Download::Glb);
    const auto it = files.find(path);
    if (it == files.end()) throw Missing("no such page or API path: '" + path + "' (docs/serve.md lists them)");
    return it->second;
}

std::pair<std::size_t, std::size_t> Api::State::range(const Query& q) const {
    const std::size_t begin = count_parameter(q, "begin", 0, SIZE_MAX / 2);
    const std::size_t end = count_parameter(q, "end", begin + options.max_frames, SIZE_MAX / 2);
    if (end <= begin) throw BadRequest("empty frame range: end must be above begin");
    if (end - begin > options.max_frames)
        throw BadRequest("at most " + std::to_string(options.max_frames) + " frames per request (asked for " +
                         std::to_string(end - begin) + "): ask for a range with begin and end");
    return {begin, end};
}

Reply Api::State::clips() {
    std::lock_guard<std::mutex> lock(db);
    const Database d(options.database);
    json::JsonWriter j;
    json::write_clip_list(j, options.database.filename().string(), d.clips(), d.packed());
    return json_reply(j);
}

Reply Api::State::clip(const Query& q) {
    const std::string& id = required(q, "id");
    const auto [begin, end] = range(q);
    Clip c;
    {
        std::lock_guard<std::mutex> lock(db);
        c = Database(options.database).load_clip(id);
    }
    const workflow::ClipPositions p = workflow::clip_positions(c, begin, end);
    json::JsonWriter j;
    json::write_clip_positions(j, id, p);
    return binary_reply(j, {&p.positions});
}

Reply Api::State::packed(const Query& q) {
    const std::string& id = required(q, "id");
    const auto [begin, end] = range(q);
    workflow::PackedComparison c;
    if (q.count("e")) {  // the clip packed alone, in memory, at this E
        const VecX e = number_list(q.at("e"), "e");
        if (e.size() != 1 || !(e(0) >= 0.001 && e(0) <= 100.0))
            throw BadRequest("query parameter 'e': one max error in cm from 0.001 to 100");
        Clip source;
        {
            std::lock_guard<std::mutex> lock(db);
            source = Database(options.database).load_clip(id);
        }
        if (source.frame_count() > 4 * options.max_frames)
            throw BadRequest("clip '" + id + "' has " + std::to_string(source.frame_count()) +
                             " frames: too long to pack on request (at most " + std::to_string(4 * options.max_frames) +
                             "); pack the database to compare it");
        c = workflow::compare_with_packed_at(source, e(0), begin, end);
    } else {
        std::lock_guard<std::mutex> lock(db);
        const Database d(options.database);
        if (!d.packed()) throw BadRequest("the database has no packed tier: pack it, or ask for a max error e");
        c = workflow::compare_with_packed(d, id, begin, end);
    }
    json::JsonWriter j;
    json::write_packed_comparison(j, id, c);
    return binary_reply(j, {&c.source.positions, &c.packed.positions, &c.errors});
}

Reply Api::State::sets() {
    std::vector<json::SetView> views;
    {
        std::lock_guard<std::mutex> lock(db);
        const Database d(options.database);
        for (const SetRecord& r : d.sets()) {
            if (r.parameter_names.empty()) continue;  // nothing to steer
            views.push_back({d.load_set(r.name), r.aligned, r.model});
        }
    }
    json::JsonWriter j;
    json::write_set_views(j, views);
    return json_reply(j);
}

LoadedModel Api::State::model(const std::string& set) {
    std::error_code ec;
    const auto stamp = std::filesystem::last_write_time(options.database, ec);
    {
        std::lock_guard<std::mutex> lock(models_mutex);
        const auto it = models.find(set);
        if (it != models.end() && !ec && it->second.stamp == stamp) return it->second;
    }
    LoadedModel m;
    m.stamp = stamp;
    {
        std::lock_guard<std::mutex> lock(db);
        const Database d(options.database);
        if (!d.has_set(set)) throw Missing("no set '" + set + "' in " + options.database.filename().string());
        m.set = d.load_set(set);
        if (!d.load_aligned_timing(set))
            throw BadRequest("set '" + set + "' is not aligned: align it before synthesizing");
        if (d.load_model(set)) m.model = workflow::load_motion_model(d, set);
        else m.model = workflow::load_naive_motion_model(d, set);
    }
    std::lock_guard<std::mutex> lock(models_mutex);
    models[set] = m;
    return m;
}

Reply Api::State::synth(const Query& q, Download as) {
    const std::string& set = required(q, "set");
    const VecX c = number_list(required(q, "c"), "c");
    const LoadedModel m = model(set);
    const auto& names = m.model->parameter_names();
    if (c.size() != m.model->parameters()) {
        std::string list;
        for (const auto& n : names) list += (list.empty() ? "" : ", ") + n;
        throw BadRequest("set '" + set + "' has " + std::to_string(names.size()) + " parameters (" + list + "), got " +
                         std::to_string(c.size()) + " values");
    }
    json::SynthesisView v;
    v.set = set;
    v.names = names;
    v.units = m.model->parameter_units();
    v.outcome = workflow::synthesize(*m.model, m.set, c);
    v.inside = workflow::inside_box(m.model->sample_parameters(), c);
    v.warnings = workflow::synthesis_warnings(*m.model, v.outcome, m.set);
    v.model = m.model->kind();
    if (as != Download::None) return download(v.outcome.clip, as, set + "_synthesized");
    const std::size_t frames = v.outcome.clip.frame_count();
    const workflow::ClipPositions p = workflow::clip_positions(v.outcome.clip, 0, std::min(frames, options.max_frames));
    json::JsonWriter j;
    json::write_synthesis_view(j, v, p);
    return binary_reply(j, {&p.positions});
}

Reply Api::State::reliability(const Query& q) {
    const std::string& set = required(q, "set");
    const LoadedModel m = model(set);
    const Eigen::Index params = m.model->parameters();
    const std::size_t x = count_parameter(q, "x", 0, 63), y = count_parameter(q, "y", params > 1 ? 1 : 0, 63);
    if (static_cast<Eigen::Index>(std::max(x, y)) >= params || (params > 1 && x == y))
        throw BadRequest("x and y must be two different parameter indices below " + std::to_string(params));
    const std::size_t n = count_parameter(q, "n", 41, 101);
    if (n < 2) throw BadRequest("query parameter 'n': at least 2 cells per axis");
    VecX base = workflow::samples_mean(*m.model);
    if (q.count("c")) {
        base = number_list(q.at("c"), "c");
        if (base.size() != params)
            throw BadRequest("query parameter 'c': the set has " + std::to_string(params) + " parameters");
    }
    const MatX& samples = m.model->sample_parameters();
    const auto gx = workflow::padded_axis(samples, {}, static_cast<Eigen::Index>(x), static_cast<Eigen::Index>(n));
    workflow::SliceAxis gy{0, base(0), base(0), 1};
    workflow::ReliabilityMap map;
    if (params > 1) {
        gy = workflow::padded_axis(samples, {}, static_cast<Eigen::Index>(y), static_cast<Eigen::Index>(n));
        map = workflow::reliability_map(*m.model, gx, gy, base);
    } else {  // one parameter: rho along its axis
        MatX queries(gx.count, 1);
        for (Eigen::Index i = 0; i < gx.count; ++i) queries(i, 0) = gx.at(i);
        map.rho = m.model->reliability_batch(queries);
        map.fraction_trusted = (map.rho.array() >= workflow::kTrustedReliability).cast<double>().mean();
    }
    json::JsonWriter j;
    json::write_reliability_slice(j, set, m.model->parameter_names(), gx, gy, map);
    return json_reply(j);
}

Reply Api::State::clip_file(const Query& q, Download as) {
    const std::string& id = required(q, "id");
    Clip c;
    {
        std::lock_guard<std::mutex> lock(db);
        c = Database(options.database).load_clip(id);
    }
    return download(c, as, id);
}

}  // namespace mocapdb::serve
