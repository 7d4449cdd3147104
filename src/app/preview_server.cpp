#include "app/preview_server.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdio>
#include <iostream>
#include <mutex>
#include <random>
#include <stdexcept>
#include <thread>

#include <httplib.h>

#include "app/interrupt.hpp"
#include "app/preview_page.hpp"

namespace wp {
namespace {

// 128 random bits as hex: the per-run part of the preview's URL that every
// request must carry, so that another web page the user visits (which can
// send requests to 127.0.0.1 but cannot read this process's stderr) can
// neither stop the render nor read its image.
std::string random_token() {
    std::random_device device;
    std::string token;
    for (int i = 0; i < 4; ++i) {
        char part[9];
        std::snprintf(part, sizeof part, "%08x", static_cast<unsigned>(device()));
        token += part;
    }
    return token;
}

// An address as a URL's host: an IPv6 address in brackets.
std::string url_host(const std::string& address) {
    return address.find(':') != std::string::npos ? "[" + address + "]" : address;
}

bool is_loopback(const std::string& address) {
    return address == "localhost" || address == "::1" || address.rfind("127.", 0) == 0;
}

} // namespace

struct PreviewServer::Impl {
    httplib::Server server;
    std::string address;
    int port = 0;
    std::string token;
    std::thread thread;
    std::mutex ended_mutex;
    std::condition_variable ended_signal;
    bool listening_ended = false; // under ended_mutex

    // The Host headers a request to a loopback address may carry: anything
    // else is a browser sent here by a name that resolves to 127.0.0.1 (DNS
    // rebinding). Empty (no check) for other addresses, where the token is
    // the guard.
    std::vector<std::string> hosts;

    std::mutex mutex; // guards what the render thread publishes
    std::string png;  // empty until the first image
    std::string status = "{}";
};

PreviewServer::PreviewServer(const std::string& address, int port)
    : impl_(std::make_unique<Impl>()) {
    Impl& impl = *impl_;
    httplib::Server& server = impl.server;
    // A browser's keep-alive connection holds a worker; enough workers, a
    // short keep-alive and a one-second read timeout leave room for a second
    // tab and the stop request while a few clients trickle bytes.
    server.new_task_queue = [] { return new httplib::ThreadPool(16); };
    server.set_keep_alive_timeout(2);
    server.set_read_timeout(1, 0);
    server.set_write_timeout(2, 0);
    server.set_payload_max_length(1 << 10); // no request here has a body worth more

    impl.token = random_token();
    const std::string base = "/" + impl.token + "/";
    server.set_pre_routing_handler(
        [&impl](const httplib::Request& request, httplib::Response& response) {
            const auto refuse = [&response](const char* why) {
                response.status = 403;
                response.set_content(why, "text/plain");
                return httplib::Server::HandlerResponse::Handled;
            };
            if (!impl.hosts.empty()) {
                const std::string host = request.get_header_value("Host");
                if (std::find(impl.hosts.begin(), impl.hosts.end(), host) == impl.hosts.end())
                    return refuse("unexpected Host header\n");
            }
            if (request.path.rfind("/" + impl.token + "/", 0) != 0)
                return refuse("this preview's address holds a per-run token: open the URL the "
                              "render printed\n");
            // A page of another origin may send a POST here (without reading the
            // answer): a cross-origin request never stops the render.
            if (request.method != "GET" && request.has_header("Origin")) {
                const std::string origin = request.get_header_value("Origin");
                const std::string host = request.get_header_value("Host");
                if (origin != "http://" + host)
                    return refuse("cross-origin request refused\n");
            }
            return httplib::Server::HandlerResponse::Unhandled;
        });

    server.Get(base, [](const httplib::Request&, httplib::Response& response) {
        response.set_content(kPreviewPage, "text/html; charset=utf-8");
    });
    server.Get(base + "image.png", [&impl](const httplib::Request&, httplib::Response& response) {
        std::string png;
        {
            std::lock_guard lock(impl.mutex);
            png = impl.png;
        }
        response.set_header("Cache-Control", "no-store");
        if (png.empty()) {
            response.status = 503;
            response.set_content("no image yet", "text/plain");
            return;
        }
        response.set_content(std::move(png), "image/png");
    });
    server.Get(base + "status.json", [&impl](const httplib::Request&, httplib::Response& response) {
        std::string status;
        {
            std::lock_guard lock(impl.mutex);
            status = impl.status;
        }
        response.set_header("Cache-Control", "no-store");
        response.set_content(std::move(status), "application/json");
    });
    server.Post(base + "stop", [](const httplib::Request&, httplib::Response& response) {
        if (request_interrupt())
            std::cerr << "\nwavepath: stop asked for on the preview page: finishing the current "
                         "wave and writing the outputs\n";
        response.set_content("stopping\n", "text/plain");
    });

    impl.address = address;
    impl.port = port == 0 ? server.bind_to_any_port(address) : port;
    if (is_loopback(address))
        for (const std::string& name : {std::string("127.0.0.1"), std::string("localhost"),
                                        std::string("[::1]"), url_host(address)})
            impl.hosts.push_back(name + ":" + std::to_string(impl.port));
    const bool bound = port == 0 ? impl.port > 0 : server.bind_to_port(address, port);
    if (!bound)
        throw std::runtime_error(
            "cannot serve the preview on " + address + ":" + std::to_string(port) + ": " +
            (port == 0 ? std::string("the address is not one of this machine's")
                       : "the port is in use or the address is not one of this machine's "
                         "(--preview 0 picks a free port)"));
    impl.thread = std::thread([&impl] {
        impl.server.listen_after_bind();
        std::lock_guard lock(impl.ended_mutex);
        impl.listening_ended = true;
        impl.ended_signal.notify_all();
    });
}

PreviewServer::~PreviewServer() {
    Impl& impl = *impl_;
    // stop() does nothing before the thread has started listening, which
    // would then go on for ever: wait for it first.
    for (;;) {
        {
            std::lock_guard lock(impl.ended_mutex);
            if (impl.server.is_running() || impl.listening_ended)
                break;
        }
        std::this_thread::sleep_for(std::chrono::milliseconds(1));
    }
    impl.server.stop();
    // Listening ends once every worker is free, which a client that keeps
    // its connection busy could put off. The render's exit never waits for
    // a client: after a short grace the server is left to the process's end
    // (its threads and state, deliberately never freed).
    std::unique_lock lock(impl.ended_mutex);
    if (impl.ended_signal.wait_for(lock, std::chrono::milliseconds(500),
                                   [&impl] { return impl.listening_ended; })) {
        lock.unlock();
        impl.thread.join();
        return;
    }
    lock.unlock();
    impl.thread.detach();
    [[maybe_unused]] Impl* left = impl_.release();
}

int PreviewServer::port() const {
    return impl_->port;
}

std::string PreviewServer::url() const {
    return "http://" + url_host(impl_->address) + ":" + std::to_string(impl_->port) + "/" +
           impl_->token + "/";
}

void PreviewServer::publish(std::vector<unsigned char> png, std::string status) {
    std::string bytes(png.begin(), png.end());
    std::lock_guard lock(impl_->mutex);
    impl_->png = std::move(bytes);
    impl_->status = std::move(status);
}

void PreviewServer::publish_status(std::string status) {
    std::lock_guard lock(impl_->mutex);
    impl_->status = std::move(status);
}

} // namespace wp
