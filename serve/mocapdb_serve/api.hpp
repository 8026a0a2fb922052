#pragma once
// The requests `mocapdb serve` answers, without the HTTP: a GET path and its query parameters in, a
// status, content type and body out (docs/serve.md lists every path). Read-only on the database: each
// request opens it anew, so it sees the last committed state while another process writes. Never
// throws from get(): bad input is a 400 with a JSON error, an unknown path a 404, a database that cannot
// be read a 500, each naming what was wrong. Threads: get() may be called from many threads at once
// (database reads are serialized: HDF5's serial build; syntheses and FK run concurrently).
#include <cstddef>
#include <filesystem>
#include <map>
#include <memory>
#include <string>

namespace mocapdb::serve {

struct ServeOptions {
    std::filesystem::path database;
    std::size_t max_frames = 20000;   ///< frames per motion reply (a longer clip is asked for by range)
    std::filesystem::path three_dir;  ///< Debian libjs-three's folder (three.min.js, OrbitControls.js)
};

struct Reply {
    int status = 200;
    std::string content_type;
    std::string body;
    std::string download_name;  ///< non-empty: sent as an attachment of this name
};

using Query = std::map<std::string, std::string>;

class Api {
public:
    /// Reads the page's three.js files (IoError naming them and the package when missing) and checks
    /// that the database opens (StoreError / IoError otherwise).
    explicit Api(ServeOptions options);
    ~Api();
    Api(const Api&) = delete;
    Api& operator=(const Api&) = delete;

    Reply get(const std::string& path, const Query& query) const;

private:
    struct State;
    std::unique_ptr<State> state_;
};

}  // namespace mocapdb::serve
