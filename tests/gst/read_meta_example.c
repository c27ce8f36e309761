/* Reads GstHandPointingMeta from the buffers that handtracker outputs.
 * Build: cc read_meta_example.c $(pkg-config --cflags --libs gstreamer-gesturecam-meta-1.0) */
#include <gst/gst.h>
#include <gst/gesturecam/gsthandpointingmeta.h>

static GstPadProbeReturn
on_buffer (GstPad * pad, GstPadProbeInfo * info, gpointer user_data)
{
  guint *frames = user_data;
  GstBuffer *buffer = GST_PAD_PROBE_INFO_BUFFER (info);
  GstHandPointingMeta *meta = gst_buffer_get_hand_pointing_meta (buffer);

  (void) pad;

  if (meta == NULL)
    return GST_PAD_PROBE_OK;
  (*frames)++;
  g_print ("frame %" G_GUINT64_FORMAT " %s", meta->frame,
      gst_hand_pointing_state_to_string (meta->state));
  if (meta->left.state == GST_HAND_POINTING_STATE_TRACKING)
    g_print (" fingertip (%.1f, %.1f) px", meta->left.fingertip_x,
        meta->left.fingertip_y);
  if (meta->flags & GST_HAND_POINTING_FLAG_HAS_3D)
    g_print (" azimuth %.1f elevation %.1f deg, fingertip z %.0f mm",
        meta->azimuth_deg, meta->elevation_deg, meta->fingertip_mm[2]);
  g_print ("\n");
  return GST_PAD_PROBE_OK;
}

int
main (int argc, char **argv)
{
  const gchar *description =
      "handscenesrc eye=left num-buffers=60 ! t.sink_left "
      "handscenesrc eye=right num-buffers=60 ! t.sink_right "
      "handtracker name=t ! fakesink name=sink";
  GstElement *pipeline, *sink;
  GstPad *pad;
  GstMessage *msg;
  GError *error = NULL;
  guint frames = 0;
  gboolean ok;

  gst_init (&argc, &argv);
  pipeline = gst_parse_launch (argc > 1 ? argv[1] : description, &error);
  if (pipeline == NULL) {
    g_printerr ("cannot build the pipeline: %s\n", error->message);
    return 1;
  }
  sink = gst_bin_get_by_name (GST_BIN (pipeline), "sink");
  pad = gst_element_get_static_pad (sink, "sink");
  gst_pad_add_probe (pad, GST_PAD_PROBE_TYPE_BUFFER, on_buffer, &frames, NULL);
  gst_object_unref (pad);
  gst_object_unref (sink);

  gst_element_set_state (pipeline, GST_STATE_PLAYING);
  msg = gst_bus_timed_pop_filtered (GST_ELEMENT_BUS (pipeline),
      GST_CLOCK_TIME_NONE, GST_MESSAGE_EOS | GST_MESSAGE_ERROR);
  ok = msg != NULL && GST_MESSAGE_TYPE (msg) == GST_MESSAGE_EOS;
  if (msg)
    gst_message_unref (msg);
  gst_element_set_state (pipeline, GST_STATE_NULL);
  gst_object_unref (pipeline);
  g_print ("%u frames with GstHandPointingMeta\n", frames);
  return ok && frames > 0 ? 0 : 1;
}
