// The live preview of `wavepath render --preview`: a small web server on its
// own thread that serves a page (preview_page.hpp) showing the image as it
// converges, with its samples per pixel, speed and error estimate, and a
// stop button that ends the render as Ctrl-C does.
//
//   GET  /TOKEN/             the page
//   GET  /TOKEN/image.png    the latest published image (503 before the first)
//   GET  /TOKEN/status.json  the latest published status
//   POST /TOKEN/stop         request_interrupt() (interrupt.hpp)
//
// TOKEN is 128 random bits drawn per run and printed only in url(): any
// other path is refused (403), so a web page the user visits cannot stop
// the render or read its image. On a loopback address the Host header must
// name it (no DNS rebinding), and a POST with an Origin header must come
// from the page's own origin. Reads time out after a second, and the
// destructor waits at most half a second for busy clients.
//
// The render thread publishes; the server's threads only copy out what was
// last published, under a mutex, so a slow browser never holds up the render.
#pragma once

#include <memory>
#include <string>
#include <vector>

namespace wp {

class PreviewServer {
  public:
    // Listens on address:port (port 0: a free one, see port()). Throws
    // std::runtime_error "cannot serve the preview on ADDRESS:PORT: ..." when
    // it cannot.
    PreviewServer(const std::string& address, int port);
    ~PreviewServer(); // stops serving and joins the thread
    PreviewServer(const PreviewServer&) = delete;
    PreviewServer& operator=(const PreviewServer&) = delete;

    int port() const;
    std::string url() const; // http://ADDRESS:PORT/TOKEN/ (an IPv6 ADDRESS in brackets)

    // `png`: an encoded PNG (image/png.hpp encode_png); `status`: a JSON object.
    void publish(std::vector<unsigned char> png, std::string status);
    void publish_status(std::string status);

  private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

} // namespace wp
