#include "app/preview_server.hpp"

#include <atomic>
#include <chrono>
#include <iostream>
#include <mutex>
#include <stdexcept>
#include <thread>

#include <httplib.h>

#include "app/interrupt.hpp"
#include "app/preview_page.hpp"

namespace wp {

struct PreviewServer::Impl {
    httplib::Server server;
    std::string address;
    int port = 0;
    std::thread thread;
    std::atomic<bool> listening_ended{false};

    std::mutex mutex; // guards what the render thread publishes
    std::string png;  // empty until the first image
    std::string status = "{}";
};

PreviewServer::PreviewServer(const std::string& address, int port)
    : impl_(std::make_unique<Impl>()) {
    Impl& impl = *impl_;
    httplib::Server& server = impl.server;
    // A browser's keep-alive connection holds a worker; a few workers and a
    // short keep-alive leave room for a second tab and the stop request.
    server.new_task_queue = [] { return new httplib::ThreadPool(4); };
    server.set_keep_alive_timeout(2);

    server.Get("/", [](const httplib::Request&, httplib::Response& response) {
        response.set_content(kPreviewPage, "text/html; charset=utf-8");
    });
    server.Get("/image.png", [&impl](const httplib::Request&, httplib::Response& response) {
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
    server.Get("/status.json", [&impl](const httplib::Request&, httplib::Response& response) {
        std::string status;
        {
            std::lock_guard lock(impl.mutex);
            status = impl.status;
        }
        response.set_header("Cache-Control", "no-store");
        response.set_content(std::move(status), "application/json");
    });
    server.Post("/stop", [](const httplib::Request&, httplib::Response& response) {
        if (request_interrupt())
            std::cerr << "\nwavepath: stop asked for on the preview page: finishing the current "
                         "wave and writing the outputs\n";
        response.set_content("stopping\n", "text/plain");
    });

    impl.address = address;
    impl.port = port == 0 ? server.bind_to_any_port(address) : port;
    const bool bound = port == 0 ? impl.port > 0 : server.bind_to_port(address, port);
    if (!bound)
        throw std::runtime_error(
            "cannot serve the preview on " + address + ":" + std::to_string(port) + ": " +
            (port == 0 ? std::string("the address is not one of this machine's")
                       : "the port is in use or the address is not one of this machine's "
                         "(--preview 0 picks a free port)"));
    impl.thread = std::thread([&impl] {
        impl.server.listen_after_bind();
        impl.listening_ended = true;
    });
}

PreviewServer::~PreviewServer() {
    // stop() does nothing before the thread has started listening, which
    // would then go on for ever: wait for it first.
    while (!impl_->server.is_running() && !impl_->listening_ended)
        std::this_thread::sleep_for(std::chrono::milliseconds(1));
    impl_->server.stop();
    if (impl_->thread.joinable())
        impl_->thread.join();
}

int PreviewServer::port() const {
    return impl_->port;
}

std::string PreviewServer::url() const {
    return "http://" + impl_->address + ":" + std::to_string(impl_->port) + "/";
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
