// One HTTP POST at a time over libsoup, on a main context of its own, so that a request
// keeps its deadline and a CancelScope's flag (net.hpp) like the socket helpers do, and a
// reply is read only up to a size limit.
#pragma once

#include "headctl/net.hpp"

#include <string>
#include <string_view>

struct _GMainContext;
struct _SoupSession;

namespace gc::headctl {

struct HttpReply {
    unsigned status = 0;
    std::string body;
};

class SoapHttpClient {
public:
    explicit SoapHttpClient(std::string url);
    ~SoapHttpClient();
    SoapHttpClient(const SoapHttpClient&) = delete;
    SoapHttpClient& operator=(const SoapHttpClient&) = delete;

    // POSTs a SOAP 1.2 message; throws net::NetError on timeout, cancellation, a failed
    // connection or a reply body over max_reply bytes.
    HttpReply post(std::string_view body, std::string_view action, net::Clock::time_point deadline,
                   std::size_t max_reply);
    // Drops the connections (the next post opens a new one).
    void reset();

private:
    std::string url_;
    _GMainContext* context_;
    _SoupSession* session_ = nullptr;
};

}  // namespace gc::headctl
