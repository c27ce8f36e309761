// Head URIs: the three schemes, defaults, IPv6, query parameters and every rejection.
#include "headctl/onvif_backend.hpp"
#include "headctl/uri.hpp"
#include "headctl/visca_backend.hpp"

#include <gtest/gtest.h>

namespace gc::headctl {
namespace {

TEST(HeadUri, ParsesEachSchemeWithItsDefaultPort)
{
    const HeadUri a = parse_head_uri("tcp://127.0.0.1:5050");
    EXPECT_EQ(a.scheme, HeadScheme::Gchp);
    EXPECT_EQ(a.host, "127.0.0.1");
    EXPECT_EQ(a.port, 5050);
    const HeadUri b = parse_head_uri("visca-udp://camera.local");
    EXPECT_EQ(b.scheme, HeadScheme::ViscaUdp);
    EXPECT_EQ(b.host, "camera.local");
    EXPECT_EQ(b.port, 52381);
    const HeadUri c = parse_head_uri("visca-tcp://10.0.0.7:5678/");
    EXPECT_EQ(c.scheme, HeadScheme::ViscaTcp);
    EXPECT_EQ(c.port, 5678);
    EXPECT_EQ(parse_head_uri("tcp://head").port, 5050);
}

TEST(HeadUri, ParsesIpv6AndQueryAndRoundTrips)
{
    const HeadUri u = parse_head_uri("visca-udp://[::1]:1259?address=2&pan_units_per_deg=-14.4");
    EXPECT_EQ(u.host, "::1");
    EXPECT_EQ(u.port, 1259);
    EXPECT_EQ(u.param("address"), "2");
    EXPECT_DOUBLE_EQ(u.number_param("pan_units_per_deg", 16, -1000, 1000), -14.4);
    EXPECT_DOUBLE_EQ(u.number_param("tilt_units_per_deg", 16, -1000, 1000), 16.0);
    EXPECT_EQ(to_string(u), "visca-udp://[::1]:1259?address=2&pan_units_per_deg=-14.4");
    EXPECT_EQ(parse_head_uri(to_string(u)).params, u.params);
    EXPECT_EQ(parse_head_uri("tcp://h:1?token=abc").param("token"), "abc");
}

TEST(HeadUri, OnvifTakesAServicePathAndItsSettings)
{
    const HeadUri u = parse_head_uri("onvif://[::1]:8080/onvif/PTZ?user=op&token=pw&pan_min_deg=0&pan_max_deg=350");
    EXPECT_EQ(u.scheme, HeadScheme::Onvif);
    EXPECT_EQ(u.host, "::1");
    EXPECT_EQ(u.port, 8080);
    EXPECT_EQ(u.path, "/onvif/PTZ");
    EXPECT_EQ(parse_head_uri(to_string(u)).path, "/onvif/PTZ");
    EXPECT_EQ(parse_head_uri("onvif://camera").port, 80);
    EXPECT_EQ(parse_head_uri("onvif://camera").path, "");
    const OnvifSettings s = OnvifSettings::from_uri(u);
    EXPECT_EQ(s.user, "op");
    EXPECT_DOUBLE_EQ(s.pan_min_deg, 0.0);
    EXPECT_DOUBLE_EQ(s.pan_max_deg, 350.0);
    EXPECT_DOUBLE_EQ(s.tilt_max_deg, 45.0);
    EXPECT_EQ(redact_uri("onvif://camera:80/x?user=op&token=pw"), "onvif://camera:80/x?user=op&token=***");
    EXPECT_THROW(parse_head_uri("onvif://camera/../etc"), std::invalid_argument);
    EXPECT_THROW(parse_head_uri("onvif://camera?address=1"), std::invalid_argument);
    EXPECT_THROW(OnvifSettings::from_uri(parse_head_uri("onvif://camera?pan_min_deg=10&pan_max_deg=-10")),
                 std::invalid_argument);
}

TEST(HeadUri, RejectsMalformedUris)
{
    for (const char* bad : {
             "",
             "127.0.0.1:5050",
             "http://host:80",
             "tcp://",
             "tcp://:5050",
             "tcp://host:",
             "tcp://host:0",
             "tcp://host:65536",
             "tcp://host:12ab",
             "tcp://host:-1",
             "tcp://ho st:1",
             "tcp://host name",
             "tcp://[::1",
             "tcp://[zz]:1",
             "tcp://[12.34]:1",
             "tcp://[]:1",
             "tcp://[::1]x",
             "tcp://[::1]:",
             "tcp://host?token",
             "tcp://host?=x",
             "tcp://host?token=",
             "tcp://host?address=1",
             "tcp://host?token=a&token=b",
             "visca-udp://h?colour=red",
             "visca-udp://h?address=1 2",
             "visca-udp://h?baud=9600",
             "visca-tcp://h?baud=9600",
             "tcp://h\x01st:1",
             "visca-serial://///",
             "visca-serial:///dev//ttyUSB0",
             "pelco-d://///dev/ttyUSB0",
             "onvif://camera//",
             "onvif://camera/onvif//PTZ",
         }) {
        EXPECT_THROW(parse_head_uri(bad), std::invalid_argument) << bad;
    }
    EXPECT_THROW(parse_head_uri("tcp://" + std::string(kMaxUriLength, 'a')), std::invalid_argument);
    EXPECT_THROW(parse_head_uri("tcp://" + std::string(254, 'a')), std::invalid_argument);
    EXPECT_THROW(parse_head_uri("tcp://[" + std::string(300, ':') + "]"), std::invalid_argument);
}

TEST(HeadUri, ErrorsNameTheOffendingPart)
{
    try {
        parse_head_uri("visca-udp://h?zoom=1");
        FAIL();
    } catch (const std::invalid_argument& e) {
        EXPECT_NE(std::string(e.what()).find("'zoom'"), std::string::npos) << e.what();
    }
}

// A token in a URI that does not parse stays out of the error, wherever it stands.
TEST(HeadUri, ErrorsDoNotShowAToken)
{
    for (const char* bad : {"tcp://head:12&token=S3CRET", "127.0.0.1:5050?token=S3CRET", "tcp://?token=S3CRET",
                            "tcp://head:1?Token=S3CRET&dance=1", "tcp://head:1?token=S3CRET?x", "ftp://token=S3CRET"}) {
        try {
            parse_head_uri(bad);
            ADD_FAILURE() << bad << " parsed";
        } catch (const std::invalid_argument& e) {
            EXPECT_EQ(std::string(e.what()).find("S3CRET"), std::string::npos) << e.what();
        }
    }
}

TEST(HeadUri, RedactionHidesEveryTokenValueAndNothingElse)
{
    EXPECT_EQ(redact_uri("tcp://127.0.0.1:5050?token=abc"), "tcp://127.0.0.1:5050?token=***");
    EXPECT_EQ(redact_uri("tcp://h:1?token=a&token=b"), "tcp://h:1?token=***&token=***");
    EXPECT_EQ(redact_uri("tcp://h:1?TOKEN=abc#x"), "tcp://h:1?TOKEN=***#x");
    EXPECT_EQ(redact_uri("visca-udp://cam?address=2&pan_units_per_deg=-14.4"),
              "visca-udp://cam?address=2&pan_units_per_deg=-14.4");
    EXPECT_EQ(redact_uri("tcp://h:1"), "tcp://h:1");
    EXPECT_EQ(redact_uri(""), "");
    EXPECT_EQ(redact_uri("tcp://h:1?token="), "tcp://h:1?token=***");
}

TEST(HeadUri, ViscaSettingsComeFromTheQuery)
{
    const auto s = ViscaSettings::from_uri(
        parse_head_uri("visca-udp://h?address=3&tilt_units_per_deg=10&pan_max_speed_dps=50&timeout_ms=250"));
    EXPECT_EQ(s.address, 3);
    EXPECT_DOUBLE_EQ(s.tilt_units_per_deg, 10.0);
    EXPECT_DOUBLE_EQ(s.pan_max_speed_dps, 50.0);
    EXPECT_EQ(s.reply_timeout.count(), 250);
    for (const char* bad :
         {"visca-udp://h?address=8", "visca-udp://h?address=1.5", "visca-udp://h?pan_units_per_deg=0",
          "visca-udp://h?pan_units_per_deg=nan", "visca-udp://h?timeout_ms=0", "visca-udp://h?tilt_max_speed_dps=abc"})
        EXPECT_THROW(ViscaSettings::from_uri(parse_head_uri(bad)), std::invalid_argument) << bad;
}

}  // namespace
}  // namespace gc::headctl
