// mocapdb serve DB.h5 [--port 8080] [--host 127.0.0.1] [--open]: the page that browses the clips,
// compares packed with source and synthesizes from sliders (docs/serve.md). Read-only on the database.
#include <signal.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <thread>

#include "commands.hpp"
#include "mocapdb/core/error.hpp"
#include "mocapdb_serve/server.hpp"

namespace mocapdb::cli {
namespace {

struct ServeArgs {
    std::string db;
    std::string host = "127.0.0.1";
    int port = 8080;
    std::size_t max_frames = 20000;
    bool open = false;
};

// SIGINT and SIGTERM write a byte to this pipe (all a signal handler may safely do, and it works
// whichever thread the signal lands on: OpenBLAS starts its threads before main); a waiting thread
// reads it and stops the server.
int stop_pipe[2] = {-1, -1};

extern "C" void on_stop_signal(int) {
    const char byte = 1;
    [[maybe_unused]] const ssize_t n = write(stop_pipe[1], &byte, 1);
}

void run_serve(const ServeArgs& a) {
    if (pipe(stop_pipe) != 0) throw IoError("serve: cannot create the stop pipe");
    struct sigaction action {};
    action.sa_handler = on_stop_signal;
    sigemptyset(&action.sa_mask);
    sigaction(SIGINT, &action, nullptr);
    sigaction(SIGTERM, &action, nullptr);
    signal(SIGPIPE, SIG_IGN);  // a client that hangs up mid-reply must not end the server

    serve::ServeOptions options;
    options.database = a.db;
    options.max_frames = a.max_frames;
    options.three_dir = MOCAPDB_THREE_DIR;
    serve::Server server(options, a.host, a.port);
    const std::string url = "http://" + (a.host.find(':') != std::string::npos ? "[" + a.host + "]" : a.host) + ":" +
                            std::to_string(server.port()) + "/";
    std::printf("mocapdb serve: %s on %s (read-only; Ctrl-C stops)\n", a.db.c_str(), url.c_str());
    if (a.host != "127.0.0.1" && a.host != "localhost" && a.host != "::1")
        std::printf("mocapdb serve: listening on %s: other machines can reach it\n", a.host.c_str());
    std::fflush(stdout);
    if (a.open && std::system(("xdg-open '" + url + "' >/dev/null 2>&1 &").c_str()) != 0)
        std::fprintf(stderr, "mocapdb serve: could not open a browser; open %s\n", url.c_str());

    std::thread waiter([&] {
        char byte = 0;
        [[maybe_unused]] const ssize_t n = read(stop_pipe[0], &byte, 1);
        server.stop();
    });
    server.run();
    on_stop_signal(0);  // wakes the waiter when run() ended by itself
    waiter.join();
    std::printf("mocapdb serve: stopped\n");
}

}  // namespace

void setup_serve(CLI::App& app) {
    auto a = std::make_shared<ServeArgs>();
    CLI::App* cmd =
        app.add_subcommand("serve", "A local web page: browse clips, packed vs source in 3D, live synthesis");
    cmd->footer(
        "Examples:\n"
        "  mocapdb serve db.h5            then open http://127.0.0.1:8080/\n"
        "  mocapdb serve db.h5 --port 0   any free port (printed)\n"
        "Read-only: another process may write the database meanwhile; each request sees the last commit.");
    cmd->add_option("db", a->db, "database (HDF5)")->required()->check(CLI::ExistingFile);
    cmd->add_option("--host", a->host, "address to listen on (default 127.0.0.1: this machine only)");
    cmd->add_option("--port", a->port, "TCP port; 0 = any free port")->check(CLI::Range(0, 65535));
    cmd->add_option("--max-frames", a->max_frames, "frames per motion reply")->check(CLI::Range(1, 1000000));
    cmd->add_flag("--open", a->open, "open the page in the default browser");
    cmd->callback([a] { run_serve(*a); });
}

}  // namespace mocapdb::cli
