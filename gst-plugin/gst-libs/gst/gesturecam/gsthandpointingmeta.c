/* GstHandPointingMeta: registration, initialisation and transforms. */
#define GST_GESTURECAM_META_API __attribute__ ((visibility ("default"))) extern
#include "gsthandpointingmeta.h"

#include <gst/video/video.h>
#include <math.h>
#include <string.h>

GType
gst_hand_pointing_meta_api_get_type (void)
{
  static GType type = 0;
  static const gchar *tags[] = {
    GST_META_TAG_VIDEO_STR, GST_META_TAG_VIDEO_SIZE_STR,
    GST_META_TAG_VIDEO_ORIENTATION_STR, NULL
  };

  if (g_once_init_enter (&type)) {
    GType api = gst_meta_api_type_register ("GstHandPointingMetaAPI", tags);
    g_once_init_leave (&type, api);
  }
  return type;
}

static void
eye_init (GstHandPointingEye * eye)
{
  memset (eye, 0, sizeof (*eye));
  eye->state = GST_HAND_POINTING_STATE_ACQUIRING;
  eye->scale = 1.0;
}

static gboolean
gst_hand_pointing_meta_init (GstMeta * meta, gpointer params, GstBuffer * buffer)
{
  GstHandPointingMeta *hmeta = (GstHandPointingMeta *) meta;

  (void) params;
  (void) buffer;
  hmeta->frame = 0;
  hmeta->state = GST_HAND_POINTING_STATE_ACQUIRING;
  hmeta->flags = GST_HAND_POINTING_FLAG_NONE;
  eye_init (&hmeta->left);
  eye_init (&hmeta->right);
  hmeta->left_gesture = hmeta->right_gesture = GST_HAND_POINTING_GESTURE_UNKNOWN;
  memset (hmeta->fingertip_mm, 0, sizeof (hmeta->fingertip_mm));
  memset (hmeta->palm_mm, 0, sizeof (hmeta->palm_mm));
  memset (hmeta->direction, 0, sizeof (hmeta->direction));
  hmeta->azimuth_deg = hmeta->elevation_deg = 0.0;
  hmeta->head_pan_deg = hmeta->head_tilt_deg = 0.0;
  hmeta->head_verge_left_deg = hmeta->head_verge_right_deg = 0.0;
  hmeta->view_x = hmeta->view_y = hmeta->view_width = hmeta->view_height = 0;
  return TRUE;
}

static void
eye_scale (GstHandPointingEye * eye, gdouble sx, gdouble sy)
{
  guint i;

  eye->x *= sx;
  eye->y *= sy;
  eye->fingertip_x *= sx;
  eye->fingertip_y *= sy;
  eye->bbox_x = (gint) (eye->bbox_x * sx + 0.5);
  eye->bbox_y = (gint) (eye->bbox_y * sy + 0.5);
  eye->bbox_width = (gint) (eye->bbox_width * sx + 0.5);
  eye->bbox_height = (gint) (eye->bbox_height * sy + 0.5);
  for (i = 0; i < eye->n_contour_points; i++) {
    eye->contour[i][0] *= (gfloat) sx;
    eye->contour[i][1] *= (gfloat) sy;
  }
  /* Anisotropic scaling changes image angles; keep the direction in the new pixels. */
  if (sx != sy) {
    gdouble a = eye->pointing_deg * G_PI / 180.0;
    eye->pointing_deg = atan2 (sin (a) * sy, cos (a) * sx) * 180.0 / G_PI;
  }
  eye->scale *= sqrt (sx * sy);
}

static gboolean
gst_hand_pointing_meta_transform (GstBuffer * dest, GstMeta * meta,
    GstBuffer * buffer, GQuark type, gpointer data)
{
  GstHandPointingMeta *src = (GstHandPointingMeta *) meta;
  GstHandPointingMeta *dst;

  (void) buffer;
  if (GST_META_TRANSFORM_IS_COPY (type)) {
    GstMetaTransformCopy *copy = (GstMetaTransformCopy *) data;
    if (copy->region)
      return TRUE;              /* a part of the buffer is not a frame: drop the meta */
    dst = gst_buffer_add_hand_pointing_meta (dest);
    if (!dst)
      return FALSE;
    memcpy ((guint8 *) dst + sizeof (GstMeta), (const guint8 *) src + sizeof (GstMeta),
        sizeof (GstHandPointingMeta) - sizeof (GstMeta));
    return TRUE;
  }

  if (GST_VIDEO_META_TRANSFORM_IS_SCALE (type)) {
    GstVideoMetaTransform *trans = (GstVideoMetaTransform *) data;
    gint in_w = GST_VIDEO_INFO_WIDTH (trans->in_info);
    gint in_h = GST_VIDEO_INFO_HEIGHT (trans->in_info);
    gint out_w = GST_VIDEO_INFO_WIDTH (trans->out_info);
    gint out_h = GST_VIDEO_INFO_HEIGHT (trans->out_info);

    if (in_w <= 0 || in_h <= 0)
      return FALSE;
    dst = gst_buffer_add_hand_pointing_meta (dest);
    if (!dst)
      return FALSE;
    memcpy ((guint8 *) dst + sizeof (GstMeta), (const guint8 *) src + sizeof (GstMeta),
        sizeof (GstHandPointingMeta) - sizeof (GstMeta));
    if (dst->flags & GST_HAND_POINTING_FLAG_FULL_VIEW) {
      gdouble sx = (gdouble) out_w / in_w;
      gdouble sy = (gdouble) out_h / in_h;
      eye_scale (&dst->left, sx, sy);
      eye_scale (&dst->right, sx, sy);
      dst->view_x = 0;
      dst->view_y = 0;
      dst->view_width = out_w;
      dst->view_height = out_h;
    }
    return TRUE;
  }

  /* Other transforms (rotation, cropping) would invalidate the 2D fields: drop. */
  return FALSE;
}

const GstMetaInfo *
gst_hand_pointing_meta_get_info (void)
{
  static const GstMetaInfo *info = NULL;

  if (g_once_init_enter ((GstMetaInfo **) & info)) {
    const GstMetaInfo *mi = gst_meta_register (GST_HAND_POINTING_META_API_TYPE,
        "GstHandPointingMeta", sizeof (GstHandPointingMeta),
        gst_hand_pointing_meta_init, NULL, gst_hand_pointing_meta_transform);
    g_once_init_leave ((GstMetaInfo **) & info, (GstMetaInfo *) mi);
  }
  return info;
}

/**
 * gst_buffer_add_hand_pointing_meta:
 * @buffer: a writable #GstBuffer
 *
 * Returns: (transfer none): a zeroed meta (state ACQUIRING, scale 1) added to @buffer
 */
GstHandPointingMeta *
gst_buffer_add_hand_pointing_meta (GstBuffer * buffer)
{
  g_return_val_if_fail (GST_IS_BUFFER (buffer), NULL);
  g_return_val_if_fail (gst_buffer_is_writable (buffer), NULL);

  return (GstHandPointingMeta *) gst_buffer_add_meta (buffer,
      GST_HAND_POINTING_META_INFO, NULL);
}

void
gst_hand_pointing_eye_set_contour (GstHandPointingEye * eye, const gfloat * xy,
    guint n)
{
  guint i;

  g_return_if_fail (eye != NULL);
  g_return_if_fail (xy != NULL || n == 0);

  if (n <= GST_HAND_POINTING_MAX_CONTOUR_POINTS) {
    /* memcpy must not be given NULL, even for 0 bytes */
    if (n > 0)
      memcpy (eye->contour, xy, (gsize) n * 2 * sizeof (gfloat));
    eye->n_contour_points = n;
    return;
  }
  for (i = 0; i < GST_HAND_POINTING_MAX_CONTOUR_POINTS; i++) {
    guint src = (guint) (((guint64) i * n) / GST_HAND_POINTING_MAX_CONTOUR_POINTS);
    eye->contour[i][0] = xy[2 * src];
    eye->contour[i][1] = xy[2 * src + 1];
  }
  eye->n_contour_points = GST_HAND_POINTING_MAX_CONTOUR_POINTS;
}

const gchar *
gst_hand_pointing_state_to_string (GstHandPointingState state)
{
  switch (state) {
    case GST_HAND_POINTING_STATE_ACQUIRING:
      return "acquiring";
    case GST_HAND_POINTING_STATE_TRACKING:
      return "tracking";
    case GST_HAND_POINTING_STATE_LOST:
      return "lost";
  }
  return "unknown";
}
