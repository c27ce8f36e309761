// Every element of the plugin: state changes up and down without failures or leaks, and
// gst-inspect-1.0 describes it without warnings.
#include "gst_fixture.hpp"

#include <algorithm>
#include <string>
#include <vector>

namespace {

std::vector<std::string> plugin_elements()
{
    std::vector<std::string> names;
    GList* features = gst_registry_get_feature_list_by_plugin(gst_registry_get(), "gesturecam");
    for (GList* l = features; l; l = l->next)
        if (GST_IS_ELEMENT_FACTORY(l->data)) names.emplace_back(GST_OBJECT_NAME(l->data));
    gst_plugin_feature_list_free(features);
    return names;
}

TEST(Elements, ThePluginHasItsThreeElements)
{
    gc::test::init_gstreamer();
    const std::vector<std::string> names = plugin_elements();
    EXPECT_NE(std::find(names.begin(), names.end(), "handtracker"), names.end());
    EXPECT_NE(std::find(names.begin(), names.end(), "handscenesrc"), names.end());
    EXPECT_NE(std::find(names.begin(), names.end(), "handoverlay"), names.end());
}

TEST(Elements, StateChangesUpAndDown)
{
    gc::test::init_gstreamer();
    const GstState order[] = {GST_STATE_READY, GST_STATE_PAUSED, GST_STATE_PLAYING, GST_STATE_PAUSED,
                              GST_STATE_READY, GST_STATE_NULL,   GST_STATE_PAUSED,  GST_STATE_NULL};
    for (const std::string& name : plugin_elements()) {
        for (int round = 0; round < 2; ++round) {
            GstElement* element = gst_element_factory_make(name.c_str(), nullptr);
            ASSERT_NE(element, nullptr) << name;
            GstElement* pipeline = gst_pipeline_new(nullptr);
            gst_bin_add(GST_BIN(pipeline), element);
            for (GstState state : order) {
                EXPECT_NE(gst_element_set_state(pipeline, state), GST_STATE_CHANGE_FAILURE)
                    << name << " to " << gst_element_state_get_name(state);
                // Unlinked sources stop with not-linked on the bus; that is expected here.
                EXPECT_NE(gst_element_get_state(pipeline, nullptr, nullptr, 5 * GST_SECOND), GST_STATE_CHANGE_FAILURE)
                    << name;
            }
            gst_object_unref(pipeline);
        }
    }
}

TEST(Elements, InspectPrintsACleanDescription)
{
    gc::test::init_gstreamer();
    for (const std::string& name : plugin_elements()) {
        gchar* out = nullptr;
        gchar* err = nullptr;
        gint status = -1;
        gchar* argv[] = {const_cast<gchar*>("gst-inspect-1.0"), const_cast<gchar*>(name.c_str()), nullptr};
        GError* error = nullptr;
        ASSERT_TRUE(
            g_spawn_sync(nullptr, argv, nullptr, G_SPAWN_SEARCH_PATH, nullptr, nullptr, &out, &err, &status, &error))
            << (error ? error->message : "");
        EXPECT_TRUE(g_spawn_check_wait_status(status, nullptr)) << name;
        EXPECT_STREQ(err, "") << name;
        const std::string text = out;
        EXPECT_NE(text.find("Element Properties:"), std::string::npos) << name;
        EXPECT_EQ(text.find("WARNING"), std::string::npos) << name;
        EXPECT_EQ(text.find("CRITICAL"), std::string::npos) << name;
        g_free(out);
        g_free(err);
    }
}

TEST(Elements, BadCalibrationFailsTheStateChangeWithTheReason)
{
    gc::test::init_gstreamer();
    const gc::test::RunResult r = gc::test::run_pipeline("videotestsrc num-buffers=2 ! t.sink_left handtracker name=t "
                                                         "calibration=/nonexistent/rig.yml ! fakesink",
                                                         10 * GST_SECOND);
    EXPECT_FALSE(r.eos);
    EXPECT_NE(r.error.find("/nonexistent/rig.yml"), std::string::npos) << r.error;
}

}  // namespace
