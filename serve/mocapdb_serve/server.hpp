#pragma once
// `mocapdb serve`'s HTTP server (Debian's cpp-httplib) over an Api: GET only, the page and the API of
// docs/serve.md; other methods get 405, request bodies are refused. Binds on construction (IoError naming
// host and port when it cannot); run() serves until stop(). Threads: a pool answers requests
// concurrently; stop() may be called from any thread (not from a signal handler).
#include <memory>
#include <string>

#include "mocapdb_serve/api.hpp"

namespace mocapdb::serve {

class Server {
public:
    /// port 0: any free port (port() tells which).
    Server(ServeOptions options, const std::string& host, int port);
    ~Server();
    Server(const Server&) = delete;
    Server& operator=(const Server&) = delete;

    int port() const;
    const std::string& host() const;
    /// Serves until stop(); returns at once if stop() came first.
    void run();
    void stop();

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace mocapdb::serve
