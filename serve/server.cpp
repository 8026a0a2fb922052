#include "mocapdb_serve/server.hpp"

#include <atomic>
#include <chrono>
#include <thread>

#include "mocapdb/core/error.hpp"
#include "mocapdb_json/view_json.hpp"
// After Eigen (through the JSON writers): <resolv.h>, which httplib includes, defines _res, a name
// Eigen's kernels use.
#include <httplib.h>

namespace mocapdb::serve {

struct Server::Impl {
    Api api;
    httplib::Server http;
    std::string host;
    int port = 0;
    std::atomic<bool> stopped{false};
    std::atomic<bool> in_run{false};

    explicit Impl(ServeOptions options) : api(std::move(options)) {}
};

Server::Server(ServeOptions options, const std::string& host, int port)
    : impl_(std::make_unique<Impl>(std::move(options))) {
    Impl& s = *impl_;
    s.host = host;
    s.http.set_payload_max_length(4096);
    s.http.set_read_timeout(10, 0);
    s.http.set_write_timeout(30, 0);
    s.http.Get(R"(/.*)", [&s](const httplib::Request& req, httplib::Response& res) {
        Query query;
        for (const auto& [key, value] : req.params) query.emplace(key, value);  // the first of repeated keys
        const Reply r = s.api.get(req.path, query);
        res.status = r.status;
        if (!r.download_name.empty())
            res.set_header("Content-Disposition", "attachment; filename=\"" + r.download_name + "\"");
        res.set_header("Cache-Control", "no-store");
        res.set_header("X-Content-Type-Options", "nosniff");
        res.set_content(r.body, r.content_type.c_str());
    });
    const auto refuse = [](const httplib::Request&, httplib::Response& res) {
        res.status = 405;
        res.set_header("Allow", "GET");
        json::JsonWriter j;
        json::write_error(j, "only GET requests are served (the server is read-only)");
        res.set_content(j.str(), "application/json");
    };
    s.http.Post(R"(/.*)", refuse);
    s.http.Put(R"(/.*)", refuse);
    s.http.Delete(R"(/.*)", refuse);
    s.http.Patch(R"(/.*)", refuse);
    s.http.Options(R"(/.*)", refuse);
    s.port = port == 0 ? s.http.bind_to_any_port(host) : (s.http.bind_to_port(host, port) ? port : -1);
    if (s.port <= 0)
        throw IoError("cannot listen on " + host + ":" + std::to_string(port) +
                      " (the port is in use, or the address is not this machine's)");
}

Server::~Server() { stop(); }

int Server::port() const { return impl_->port; }
const std::string& Server::host() const { return impl_->host; }

void Server::run() {
    impl_->in_run = true;
    if (!impl_->stopped) impl_->http.listen_after_bind();
    impl_->in_run = false;
}

void Server::stop() {
    impl_->stopped = true;
    // A stop between run()'s check and the listening loop's start would be lost: repeat until the
    // loop has either not been entered or has ended (a few milliseconds at most).
    for (int attempt = 0; attempt < 500; ++attempt) {
        impl_->http.stop();
        if (!impl_->in_run) return;
        std::this_thread::sleep_for(std::chrono::milliseconds(2));
    }
}

}  // namespace mocapdb::serve
