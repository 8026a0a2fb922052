// `mocapdb serve`'s API on a real database (subject 16's walks: imported, a set with measured turn and
// speed, aligned, compressed, packed at 1 cm): every path, the motion replies against the library's own
// FK and error measurement, bad input, path traversal; then over HTTP: the page, methods, 50 concurrent
// clients and a clean stop.
#include <atomic>
#include <chrono>
#include <cstring>
#include <fstream>
#include <thread>

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include "../workflow/walk_database.hpp"
#include "gltf_reader.hpp"
#include "mocapdb/io/gltf_writer.hpp"
#include "mocapdb/workflow/synthesis_step.hpp"
#include "mocapdb/motion/forward_kinematics.hpp"
#include "mocapdb/packing/error_stats.hpp"
#include "mocapdb/store/database.hpp"
#include "mocapdb/workflow/load_model.hpp"
#include "mocapdb/workflow/pack_collection.hpp"
#include "mocapdb_serve/api.hpp"
#include "mocapdb_serve/server.hpp"
// After Eigen: <resolv.h> (included by httplib) defines _res, a name Eigen's kernels use.
#include <httplib.h>

using namespace mocapdb;
using nlohmann::json;

namespace {

struct ServeFixture {
    test::WalkDatabase walks;
    serve::ServeOptions options;
};

const ServeFixture& fixture() {
    static const ServeFixture f = [] {
        ServeFixture s;
        s.walks = test::make_walk_database("serve", test::WalkStage::Compressed);
        workflow::PackDatabaseOptions pack;
        pack.max_error_cm = 1.0;
        workflow::pack_database(s.walks.path, pack);
        s.options.database = s.walks.path;
        s.options.three_dir = MOCAPDB_THREE_DIR;
        s.options.max_frames = 5000;
        return s;
    }();
    return f;
}

struct Motion {
    json header;
    std::vector<float> floats;
};

Motion motion_of(const serve::Reply& r) {
    REQUIRE(r.status == 200);
    REQUIRE(r.content_type == "application/octet-stream");
    std::uint32_t n = 0;
    REQUIRE(r.body.size() >= 4);
    for (int k = 0; k < 4; ++k) n |= static_cast<std::uint32_t>(static_cast<unsigned char>(r.body[k])) << (8 * k);
    Motion m;
    m.header = json::parse(r.body.substr(4, n));
    const std::size_t at = 4 + n + (4 - n % 4) % 4;
    REQUIRE((r.body.size() - at) % 4 == 0);
    m.floats.resize((r.body.size() - at) / 4);
    std::memcpy(m.floats.data(), r.body.data() + at, r.body.size() - at);
    return m;
}

json json_of(const serve::Reply& r, int status = 200) {
    INFO(r.body);
    REQUIRE(r.status == status);
    REQUIRE(r.content_type == "application/json");
    return json::parse(r.body);
}

}  // namespace

TEST_CASE("serve: the clip list and a clip's positions are the stored clips' FK", "[serve]") {
    MOCAPDB_REQUIRE_SHARED(test::datasets_dir() / "cmu-asfamc");
    const serve::Api api(fixture().options);
    const json list = json_of(api.get("/api/clips", {}));
    CHECK(list["clips"].size() == 12);
    CHECK(list["packed_max_error_cm"] == 1.0);
    const Motion m = motion_of(api.get("/api/clip", {{"id", "16_15"}, {"begin", "10"}, {"end", "60"}}));
    const Clip clip = Database(fixture().walks.path).load_clip("16_15");
    const std::size_t joints = clip.skeleton->size();
    CHECK(m.header["frames"] == 50);
    CHECK(m.header["begin"] == 10);
    CHECK(m.header["joints"].size() == joints);
    REQUIRE(m.floats.size() == 50 * joints * 3);
    GlobalPose pose;
    double worst = 0.0;
    for (std::size_t f = 10; f < 60; ++f) {
        forward_kinematics(*clip.skeleton, clip.frame(f), pose);
        for (std::size_t j = 0; j < joints; ++j)
            for (int k = 0; k < 3; ++k)
                worst = std::max(worst, std::abs(pose.positions[j](k) - m.floats[((f - 10) * joints + j) * 3 + k]));
    }
    CHECK(worst < 1e-3);  // float32 of positions up to a few metres
}

TEST_CASE("serve: packed vs source gives the error the library measures, within the tier's bound", "[serve]") {
    MOCAPDB_REQUIRE_SHARED(test::datasets_dir() / "cmu-asfamc");
    const serve::Api api(fixture().options);
    const Motion m = motion_of(api.get("/api/packed", {{"id", "16_11"}}));
    const Database db(fixture().walks.path);
    const Clip source = db.load_clip("16_11");
    const Clip packed = db.load_clip_packed("16_11");
    packing::ErrorAccumulator acc;
    packing::add_position_errors(joint_positions(source), joint_positions(packed), acc);
    const double max_cm = acc.stats().max_cm;
    CHECK(m.header["max_cm"].get<double>() == Approx(max_cm).epsilon(1e-12));
    CHECK(m.header["rmse_cm"].get<double>() == Approx(acc.stats().rmse_cm).epsilon(1e-9));
    CHECK(max_cm <= 1.0 + 1e-4);
    CHECK(max_cm > 0.0);
    const std::size_t n = m.header["frames"].get<std::size_t>() * m.header["joints"].size();
    REQUIRE(m.floats.size() == 7 * n);  // source, packed (3 each), errors
    float largest = 0.0f;
    for (std::size_t i = 6 * n; i < 7 * n; ++i) largest = std::max(largest, m.floats[i]);
    CHECK(largest == Approx(max_cm).epsilon(1e-6));
}

TEST_CASE("serve: a synthesis from the stored model, its reliability the model's", "[serve]") {
    MOCAPDB_REQUIRE_SHARED(test::datasets_dir() / "cmu-asfamc");
    const serve::Api api(fixture().options);
    const json sets = json_of(api.get("/api/sets", {}));
    REQUIRE(sets["sets"].size() == 1);
    CHECK(sets["sets"][0]["name"] == "walks");
    CHECK(sets["sets"][0]["parameters"].size() == 2);
    CHECK(sets["sets"][0]["values"].size() == 12);
    const Motion a = motion_of(api.get("/api/synth", {{"set", "walks"}, {"c", "0.1,120"}}));
    const Motion b = motion_of(api.get("/api/synth", {{"set", "walks"}, {"c", "0.1,160"}}));
    const auto model = workflow::load_motion_model(Database(fixture().walks.path), "walks");
    VecX c(2);
    c << 0.1, 120.0;
    CHECK(a.header["reliability"].get<double>() == Approx(model->reliability_batch(c.transpose())(0)).epsilon(1e-12));
    CHECK(a.header["parameters"][1]["requested"] == 120.0);
    CHECK(a.header["parameters"][1]["measured"].is_number());
    CHECK(a.floats != b.floats);  // another speed, another motion
    const json map = json_of(api.get("/api/reliability", {{"set", "walks"}, {"n", "11"}}));
    CHECK(map["rho"].size() == 121);
    const serve::Reply bvh = api.get("/api/synth.bvh", {{"set", "walks"}, {"c", "0.1,120"}});
    CHECK(bvh.status == 200);
    CHECK(bvh.body.rfind("HIERARCHY", 0) == 0);
    CHECK(bvh.download_name == "walks_synthesized.bvh");
}

TEST_CASE("serve: the synthesized motion's glTF download reads back as its FK (assimp)", "[serve][gltf]") {
    MOCAPDB_REQUIRE_SHARED(test::datasets_dir() / "cmu-asfamc");
    const serve::Api api(fixture().options);
    const serve::Reply glb = api.get("/api/synth.glb", {{"set", "walks"}, {"c", "-0.2,105"}});
    REQUIRE(glb.status == 200);
    CHECK(glb.content_type == "model/gltf-binary");
    CHECK(glb.download_name == "walks_synthesized.glb");
    test::TempDir dir("serve_glb");
    {
        std::ofstream out(dir / "synth.glb", std::ios::binary);
        out << glb.body;
    }
    const Database db(fixture().walks.path);
    const auto model = workflow::load_motion_model(db, "walks");
    VecX c(2);
    c << -0.2, 105.0;
    const Clip synthesized = workflow::synthesize(*model, db.load_set("walks"), c).clip;
    const test::GltfDifference d = test::gltf_difference(dir / "synth.glb", synthesized);
    INFO("largest difference " << d.max_cm << " cm (" << d.where << ")");
    CHECK(d.max_cm <= 1e-3);
}

TEST_CASE("serve: bad requests get a 400 or 404 with a message, never a crash", "[serve]") {
    MOCAPDB_REQUIRE_SHARED(test::datasets_dir() / "cmu-asfamc");
    const serve::Api api(fixture().options);
    const auto error = [&](const std::string& path, const serve::Query& q, int status, const std::string& text) {
        const json e = json_of(api.get(path, q), status);
        INFO(path << " -> " << e.dump());
        CHECK(e["error"].get<std::string>().find(text) != std::string::npos);
    };
    error("/api/clip", {}, 400, "missing query parameter 'id'");
    error("/api/clip", {{"id", "no_such_clip"}}, 404, "no such clip");
    error("/api/clip", {{"id", "16_11"}, {"begin", "-3"}}, 400, "whole number");
    error("/api/clip", {{"id", "16_11"}, {"begin", "100000"}}, 400, "beyond");
    error("/api/clip", {{"id", "16_11"}, {"begin", "0"}, {"end", "9000"}}, 400, "at most 5000 frames");
    error("/api/clip", {{"id", "16_11"}, {"begin", "9"}, {"end", "3"}}, 400, "empty frame range");
    error("/api/synth", {{"set", "walks"}, {"c", "0.1"}}, 400, "has 2 parameters (turn, speed), got 1");
    error("/api/synth", {{"set", "walks"}, {"c", "0.1,fast"}}, 400, "'fast' is not a finite number");
    error("/api/synth", {{"set", "walks"}, {"c", "nan,1"}}, 400, "not a finite number");
    error("/api/synth", {{"set", "walks"}, {"c", "1e999,1"}}, 400, "not a finite number");
    error("/api/synth", {{"set", "nope"}, {"c", "1,1"}}, 404, "no set 'nope'");
    error("/api/reliability", {{"set", "walks"}, {"x", "1"}, {"y", "1"}}, 400, "two different parameter");
    error("/api/reliability", {{"set", "walks"}, {"n", "5000"}}, 400, "from 0 to 101");
    for (const char* path : {"/../etc/passwd", "/etc/passwd", "/api/../index.html", "/..%2f..%2fetc%2fpasswd",
                             "//etc/passwd", "/web/app.js", "/C:/Windows/win.ini", "/api/clips/../../x"})
        error(path, {}, 404, "no such page");
    CHECK(api.get("/", {}).body.find("<title>mocapdb</title>") != std::string::npos);
    CHECK(api.get("/app.js", {}).status == 200);
    CHECK(api.get("/three.min.js", {}).body.size() > 100000);
}

TEST_CASE("serve: over HTTP, GET only, 50 concurrent clients, a clean stop", "[serve]") {
    MOCAPDB_REQUIRE_SHARED(test::datasets_dir() / "cmu-asfamc");
    serve::Server server(fixture().options, "127.0.0.1", 0);
    REQUIRE(server.port() > 0);
    std::thread running([&] { server.run(); });
    httplib::Client probe("127.0.0.1", server.port());
    for (int attempt = 0; attempt < 200 && !probe.Get("/api/clips"); ++attempt)
        std::this_thread::sleep_for(std::chrono::milliseconds(10));
    const auto page = probe.Get("/");
    REQUIRE(page);
    CHECK(page->status == 200);
    CHECK(page->get_header_value("Content-Type") == "text/html");
    const auto post = probe.Post("/api/clips", "x", "text/plain");
    REQUIRE(post);
    CHECK(post->status == 405);
    const auto traversal = probe.Get("/../../etc/passwd");
    REQUIRE(traversal);
    CHECK(traversal->status != 200);
    const auto encoded = probe.Get("/%2e%2e/%2e%2e/etc/passwd");
    REQUIRE(encoded);
    CHECK(encoded->status != 200);

    std::atomic<int> ok{0}, failed{0};
    std::vector<std::thread> clients;
    for (int k = 0; k < 50; ++k)
        clients.emplace_back([&, k] {
            httplib::Client c("127.0.0.1", server.port());
            c.set_read_timeout(120, 0);
            const auto r = k % 2 ? c.Get("/api/synth?set=walks&c=0.1," + std::to_string(100 + k)) : c.Get("/api/clips");
            (r && r->status == 200 ? ok : failed)++;
        });
    for (auto& t : clients) t.join();
    CHECK(ok == 50);
    CHECK(failed == 0);

    server.stop();  // run() returns (a hang here is the test's timeout)
    running.join();
    CHECK(!httplib::Client("127.0.0.1", server.port()).Get("/api/clips"));
}
