// GCHP/1 parsing and formatting: round trips and every error path.
#include "headctl/protocol.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

namespace gc::headctl {
namespace {

enum class Parser { Request, Reply };

// The code of the ProtocolError the parser throws on `line` (a failure where it accepts it).
ErrorCode error_of(Parser parser, std::string_view line)
{
    try {
        if (parser == Parser::Request)
            parse_request(line);
        else
            parse_reply(line);
    } catch (const ProtocolError& e) {
        EXPECT_NE(std::string(e.what()), "");
        return e.code();
    }
    ADD_FAILURE() << "accepted: " << line;
    return ErrorCode::Internal;
}

TEST(Protocol, ParsesMoveWithIdAndAxes)
{
    const Request r = parse_request("#12 MOVE ABS pan=10.5 tilt=-3");
    ASSERT_TRUE(r.id);
    EXPECT_EQ(*r.id, 12u);
    EXPECT_EQ(r.command, Command::MoveAbsolute);
    EXPECT_DOUBLE_EQ(r.values.get(Axis::Pan), 10.5);
    EXPECT_DOUBLE_EQ(r.values.get(Axis::Tilt), -3.0);
    EXPECT_FALSE(r.values.has(Axis::VergeLeft));
}

TEST(Protocol, VerbsAreCaseInsensitiveAndCarriageReturnIsIgnored)
{
    EXPECT_EQ(parse_request("status\r").command, Command::Status);
    EXPECT_EQ(parse_request("  move  vel\tverge_l=2e1 ").command, Command::MoveVelocity);
    EXPECT_DOUBLE_EQ(parse_request("move rel verge_r=-0.25").values.get(Axis::VergeRight), -0.25);
}

TEST(Protocol, RequestRoundTrips)
{
    std::vector<Request> requests;
    Request move;
    move.id = 4294967295u;
    move.command = Command::MoveVelocity;
    move.values.set(Axis::Pan, -12.3456);
    move.values.set(Axis::VergeRight, 99999.0);
    requests.push_back(move);
    for (Command c : {Command::Status, Command::Stop, Command::Home, Command::Limits, Command::Quit}) {
        Request r;
        r.command = c;
        requests.push_back(r);
    }
    Request auth;
    auth.id = 0;
    auth.command = Command::Auth;
    auth.token = "s3cr3t-token";
    requests.push_back(auth);
    for (const Request& r : requests) EXPECT_EQ(parse_request(format_request(r)), r) << format_request(r);
}

// Lines a parser refuses, grouped by the error code they earn.
struct Refused {
    std::string name;
    Parser parser;
    ErrorCode code;
    std::vector<std::string> lines;
};

const std::string kOverLongRequest = "MOVE ABS pan=1" + std::string(kMaxLineLength, ' ');

const Refused kRefused[] = {
    {"UnknownCommands", Parser::Request, ErrorCode::UnknownCommand, {"JUMP pan=1", "#3 FLY"}},
    {"BadNumbers",
     Parser::Request,
     ErrorCode::BadArgument,
     {"MOVE ABS pan=abc", "MOVE ABS pan=1.5x", "MOVE ABS pan=", "MOVE ABS pan=+1", "MOVE ABS pan=1e6",
      "MOVE ABS pan=1e400", "MOVE VEL pan=nan", "MOVE VEL pan=NaN", "MOVE VEL pan=-nan", "MOVE VEL pan=inf",
      "MOVE VEL pan=-inf", "MOVE VEL pan=infinity"}},
    {"OverLongRequest", Parser::Request, ErrorCode::LineTooLong, {kOverLongRequest}},
    {"OverLongReply", Parser::Reply, ErrorCode::LineTooLong, {"OK " + std::string(kMaxLineLength, 'x')}},
    {"MalformedRequests",
     Parser::Request,
     ErrorCode::Syntax,
     {"", "#7", "MOVE", "MOVE ABS", "MOVE SIDEWAYS pan=1", "MOVE ABS pan", "MOVE ABS =3", "STATUS now", "AUTH",
      "AUTH a b", "#x STATUS", "#99999999999 STATUS", "#4294967296 STATUS", std::string("STATUS\0", 7), "STATUS \x7f"}},
    {"BadRequestArguments",
     Parser::Request,
     ErrorCode::BadArgument,
     {"MOVE ABS roll=3", "MOVE ABS pan=1 pan=2", "AUTH " + std::string(kMaxTokenLength + 1, 'k')}},
    {"MalformedReplies",
     Parser::Reply,
     ErrorCode::Syntax,
     {"", "MAYBE", "ERR #1", "OK #1 STATE t=1 pan=0 tilt=0 verge_l=0 moving=0,0,0,0",
      "OK #1 STATE t=1 pan=0 tilt=0 verge_l=0 verge_r=0 moving=0,0,2,0",
      "OK #1 STATE t=1 pan=0 tilt=0 verge_l=0 verge_r=0 moving=0,0,0", "OK LIMITS pan=1:2:3:4",
      "OK LIMITS pan=-1:1:3 tilt=-1:1:1:1 verge_l=-1:1:1:1 verge_r=-1:1:1:1", "OK #1 WEATHER sunny"}},
    {"BadReplyArguments",
     Parser::Reply,
     ErrorCode::BadArgument,
     {"ERR #1 abc text", "OK #1 STATE t=x pan=0 tilt=0 verge_l=0 verge_r=0 moving=0,0,0,0",
      "OK #1 STATE t=1 pan=inf tilt=0 verge_l=0 verge_r=0 moving=0,0,0,0",
      "OK LIMITS pan=1:-1:3:4 tilt=-1:1:1:1 verge_l=-1:1:1:1 verge_r=-1:1:1:1"}},
};

class Refusal : public ::testing::TestWithParam<Refused> {};

TEST_P(Refusal, EachLineEarnsItsErrorCode)
{
    for (const std::string& line : GetParam().lines)
        EXPECT_EQ(error_of(GetParam().parser, line), GetParam().code) << line;
}

INSTANTIATE_TEST_SUITE_P(Protocol, Refusal, ::testing::ValuesIn(kRefused),
                         [](const auto& info) { return info.param.name; });

// Formats `r`, checks the line against `expected`, and parses it back.
Reply round_trip(const Reply& r, const std::string& expected)
{
    const std::string line = format_reply(r);
    EXPECT_EQ(line, expected);
    return parse_reply(line);
}

TEST(Protocol, PeeksTheIdOfAMalformedRequest)
{
    EXPECT_EQ(peek_request_id("#42 MOVE ABS pan=nan"), 42u);
    EXPECT_EQ(peek_request_id("  #7"), 7u);
    EXPECT_FALSE(peek_request_id("MOVE #42"));
    EXPECT_FALSE(peek_request_id("#4x STATUS"));
    EXPECT_FALSE(peek_request_id("#99999999999 STATUS"));
}

TEST(Protocol, StateReplyRoundTrips)
{
    Reply r;
    r.id = 9;
    r.body = ReplyBody::State;
    r.state.server_time_us = 123456789012;
    r.state.pose = HeadPose{12.5, -3.25, 4.0, -4.0, 2.5};
    r.state.moving = {false, true, false, false, true};
    const Reply back =
        round_trip(r, "OK #9 STATE t=123456789012 pan=12.5 tilt=-3.25 verge_l=4 verge_r=-4 zoom=2.5 moving=0,1,0,0,1");
    EXPECT_TRUE(back.ok);
    EXPECT_EQ(back.id, 9u);
    ASSERT_EQ(back.body, ReplyBody::State);
    EXPECT_EQ(back.state.server_time_us, 123456789012);
    EXPECT_DOUBLE_EQ(back.state.pose.tilt_deg, -3.25);
    EXPECT_DOUBLE_EQ(back.state.pose.verge_right_deg, -4.0);
    EXPECT_DOUBLE_EQ(back.state.pose.zoom, 2.5);
    EXPECT_EQ(back.state.moving, r.state.moving);
}

TEST(Protocol, AHeadWithoutZoomReportsFourAxesAndReadsAsTheWidestView)
{
    const Reply r = parse_reply("OK STATE t=5 pan=1 tilt=2 verge_l=3 verge_r=4 moving=0,0,1,0");
    EXPECT_DOUBLE_EQ(r.state.pose.zoom, 1.0);
    EXPECT_TRUE(r.state.moving[2]);
    EXPECT_FALSE(r.state.moving[4]);
    const Reply l = parse_reply("OK LIMITS pan=-1:1:1:1 tilt=-1:1:1:1 verge_l=-1:1:1:1 verge_r=-1:1:1:1");
    EXPECT_EQ(l.limits[Axis::Zoom], (AxisLimits{1.0, 1.0, 1.0, 1.0}));
    EXPECT_THROW(parse_reply("OK STATE t=5 pan=1 tilt=2 verge_l=3 verge_r=4 zoom=0.5 moving=0,0,0,0,0"), ProtocolError);
    EXPECT_THROW(parse_reply("OK STATE t=5 pan=1 tilt=2 verge_l=3 verge_r=4 moving=0,0,0,0,0,0"), ProtocolError);
    EXPECT_THROW(parse_reply("OK LIMITS pan=-1:1:1:1 tilt=-1:1:1:1 verge_l=-1:1:1:1 verge_r=-1:1:1:1 zoom=0.5:4:1:1"),
                 ProtocolError);
}

TEST(Protocol, PresetsAreSavedAndRecalledByNumber)
{
    const Request save = parse_request("#4 preset save 12");
    EXPECT_EQ(save.command, Command::PresetSave);
    EXPECT_EQ(save.preset, 12);
    EXPECT_EQ(format_request(save), "#4 PRESET SAVE 12");
    const Request recall = parse_request("PRESET RECALL 255");
    EXPECT_EQ(recall.command, Command::PresetRecall);
    EXPECT_EQ(format_request(recall), "PRESET RECALL 255");
    for (const char* bad :
         {"PRESET SAVE", "PRESET SAVE 256", "PRESET SAVE -1", "PRESET FORGET 1", "PRESET SAVE 1 2", "PRESET RECALL x"})
        EXPECT_THROW(parse_request(bad), ProtocolError) << bad;
    Greeting g;
    g.caps.presets = true;
    EXPECT_EQ(format_greeting(g), "HELLO GCHP/1 axes=pan,tilt,verge_l,verge_r,zoom caps=abs,rel,vel,preset");
    EXPECT_TRUE(parse_greeting(format_greeting(g)).caps.presets);
}

TEST(Protocol, ZoomIsAnAxisOfMoves)
{
    const Request r = parse_request("#3 MOVE ABS zoom=2 pan=1");
    EXPECT_DOUBLE_EQ(r.values.get(Axis::Zoom), 2.0);
    EXPECT_EQ(format_request(r), "#3 MOVE ABS pan=1 zoom=2");
}

TEST(Protocol, NumbersKeepFourDecimals)
{
    Request r;
    r.command = Command::MoveAbsolute;
    r.values.set(Axis::Pan, 1.0 / 3.0);
    r.values.set(Axis::Tilt, -0.00001);
    EXPECT_EQ(format_request(r), "MOVE ABS pan=0.3333 tilt=0");
    r.values.set(Axis::Pan, std::nan(""));
    EXPECT_THROW(format_request(r), std::invalid_argument);
}

TEST(Protocol, LimitsReplyRoundTripsWithinTheLineBound)
{
    Reply r;
    r.body = ReplyBody::Limits;
    for (Axis a : kAllAxes) r.limits[a] = AxisLimits{-99999.1234, 99999.1234, 99999.1234, 99999.1234};
    r.limits[Axis::Zoom] = AxisLimits{1.0, 99999.1234, 99999.1234, 99999.1234};
    const std::string line = format_reply(r);
    EXPECT_LE(line.size(), kMaxLineLength);
    const Reply back = parse_reply(line);
    ASSERT_EQ(back.body, ReplyBody::Limits);
    EXPECT_EQ(back.limits, r.limits);
}

TEST(Protocol, ErrorReplyRoundTrips)
{
    const Reply r = make_error_reply(5, ErrorCode::OutOfRange, "pan target 300 deg is outside [-170, 170]");
    const Reply back = round_trip(r, "ERR #5 416 pan target 300 deg is outside [-170, 170]");
    EXPECT_FALSE(back.ok);
    EXPECT_EQ(back.id, 5u);
    EXPECT_EQ(back.error, ErrorCode::OutOfRange);
    EXPECT_EQ(back.message, r.message);
    // Without an id, and an unknown code of a later version keeps its class.
    EXPECT_EQ(parse_reply("ERR 401 authenticate first").error, ErrorCode::AuthRequired);
    EXPECT_EQ(parse_reply("ERR 499 new thing").error, ErrorCode::BadArgument);
    EXPECT_EQ(parse_reply("ERR 599 new thing").error, ErrorCode::Internal);
}

TEST(Protocol, ErrorMessagesAreSanitisedAndBounded)
{
    const Reply r = make_error_reply(1, ErrorCode::Syntax, std::string("bad\nline\x01") + std::string(2000, 'z'));
    const std::string line = format_reply(r);
    EXPECT_LE(line.size(), kMaxLineLength);
    EXPECT_EQ(line.find('\n'), std::string::npos);
    EXPECT_NO_THROW(parse_reply(line));
    // Cut at any position, even next to a blank, the line formats back to itself.
    for (std::size_t k = 495; k < 510; ++k) {
        const Reply cut = make_error_reply(std::nullopt, ErrorCode::Internal, std::string(k, 'a') + " b c d e f g h");
        const std::string once = format_reply(cut);
        EXPECT_EQ(format_reply(parse_reply(once)), once) << k;
        EXPECT_NE(once.back(), ' ');
    }
}

TEST(Protocol, RepliesIgnoreUnknownFieldsOfLaterVersions)
{
    const Reply r = parse_reply("OK #1 STATE t=5 pan=1 tilt=2 verge_l=3 verge_r=4 moving=1,0,0,1 temp=41.5");
    EXPECT_EQ(r.state.server_time_us, 5);
    EXPECT_DOUBLE_EQ(r.state.pose.verge_right_deg, 4.0);
}

TEST(Protocol, GreetingRoundTripsAndChecksItsShape)
{
    Greeting g;
    EXPECT_EQ(format_greeting(g), "HELLO GCHP/1 axes=pan,tilt,verge_l,verge_r,zoom caps=abs,rel,vel");
    g.caps.auth_required = true;
    g.axes = {true, true, false, false, true};
    EXPECT_EQ(parse_greeting(format_greeting(g)), g);
    EXPECT_EQ(parse_greeting("HELLO GCHP/2 axes=pan caps=abs,teleport").version, 2);
    EXPECT_THROW(parse_greeting("HELLO HTTP/1.1"), ProtocolError);
    EXPECT_THROW(parse_greeting("HELLO GCHP/x axes=pan caps=abs"), ProtocolError);
    EXPECT_THROW(parse_greeting("HELLO GCHP/1 axes=pan"), ProtocolError);
    EXPECT_THROW(parse_greeting("HELLO GCHP/1 axes=roll caps=abs"), ProtocolError);
    EXPECT_THROW(parse_greeting("GOODBYE"), ProtocolError);
}

}  // namespace
}  // namespace gc::headctl
