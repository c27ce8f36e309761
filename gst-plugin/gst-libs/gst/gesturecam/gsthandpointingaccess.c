/* GstHandPointingMeta's accessors: what a language binding calls instead of reading the
 * record's fields, whose layout bindings never see. */
#define GST_GESTURECAM_META_API __attribute__ ((visibility ("default"))) extern
#include "gsthandpointingmeta.h"

/* The view's estimate, or NULL for the right view of a mono meta. */
static const GstHandPointingEye *
view_eye (const GstHandPointingMeta * meta, GstHandPointingView view)
{
  if (view == GST_HAND_POINTING_VIEW_LEFT)
    return &meta->left;
  if (view == GST_HAND_POINTING_VIEW_RIGHT
      && (meta->flags & GST_HAND_POINTING_FLAG_STEREO))
    return &meta->right;
  return NULL;
}

/**
 * gst_hand_pointing_meta_from_buffer:
 * @buffer: a #GstBuffer
 *
 * Returns: (transfer none) (nullable): the buffer's #GstHandPointingMeta, or %NULL when it
 *   has none. It lives as long as the buffer.
 */
GstHandPointingMeta *
gst_hand_pointing_meta_from_buffer (GstBuffer * buffer)
{
  g_return_val_if_fail (GST_IS_BUFFER (buffer), NULL);
  return gst_buffer_get_hand_pointing_meta (buffer);
}

/**
 * gst_hand_pointing_meta_get_frame:
 * @meta: a #GstHandPointingMeta
 *
 * Returns: the index of the stereo pair since the tracker started
 */
guint64
gst_hand_pointing_meta_get_frame (const GstHandPointingMeta * meta)
{
  g_return_val_if_fail (meta != NULL, 0);
  return meta->frame;
}

/**
 * gst_hand_pointing_meta_get_state:
 * @meta: a #GstHandPointingMeta
 *
 * Returns: the tracking state (tracking only when every tracked view tracks)
 */
GstHandPointingState
gst_hand_pointing_meta_get_state (const GstHandPointingMeta * meta)
{
  g_return_val_if_fail (meta != NULL, GST_HAND_POINTING_STATE_ACQUIRING);
  return meta->state;
}

/**
 * gst_hand_pointing_meta_get_flags:
 * @meta: a #GstHandPointingMeta
 *
 * Returns: which parts of the meta are valid
 */
GstHandPointingFlags
gst_hand_pointing_meta_get_flags (const GstHandPointingMeta * meta)
{
  g_return_val_if_fail (meta != NULL, GST_HAND_POINTING_FLAG_NONE);
  return (GstHandPointingFlags) meta->flags;
}

/**
 * gst_hand_pointing_meta_get_direction:
 * @meta: a #GstHandPointingMeta
 * @azimuth_deg: (out) (optional): the pointing direction's azimuth, degrees, positive to the right
 * @elevation_deg: (out) (optional): its elevation, degrees, positive up
 *
 * The 3D pointing direction in the left camera's frame.
 *
 * Returns: %TRUE when the direction is known (%GST_HAND_POINTING_FLAG_HAS_3D); the outputs
 *   are left alone otherwise
 */
gboolean
gst_hand_pointing_meta_get_direction (const GstHandPointingMeta * meta,
    gdouble * azimuth_deg, gdouble * elevation_deg)
{
  g_return_val_if_fail (meta != NULL, FALSE);
  if (!(meta->flags & GST_HAND_POINTING_FLAG_HAS_3D))
    return FALSE;
  if (azimuth_deg)
    *azimuth_deg = meta->azimuth_deg;
  if (elevation_deg)
    *elevation_deg = meta->elevation_deg;
  return TRUE;
}

/**
 * gst_hand_pointing_meta_get_fingertip_mm:
 * @meta: a #GstHandPointingMeta
 * @x: (out) (optional): millimetres, to the right of the left camera
 * @y: (out) (optional): millimetres, down
 * @z: (out) (optional): millimetres, forward
 *
 * Returns: %TRUE when the 3D fingertip is known (%GST_HAND_POINTING_FLAG_HAS_3D)
 */
gboolean
gst_hand_pointing_meta_get_fingertip_mm (const GstHandPointingMeta * meta,
    gdouble * x, gdouble * y, gdouble * z)
{
  g_return_val_if_fail (meta != NULL, FALSE);
  if (!(meta->flags & GST_HAND_POINTING_FLAG_HAS_3D))
    return FALSE;
  if (x)
    *x = meta->fingertip_mm[0];
  if (y)
    *y = meta->fingertip_mm[1];
  if (z)
    *z = meta->fingertip_mm[2];
  return TRUE;
}

/**
 * gst_hand_pointing_meta_get_head_pose:
 * @meta: a #GstHandPointingMeta
 * @pan_deg: (out) (optional): the head's pan at capture, degrees
 * @tilt_deg: (out) (optional): its tilt
 * @verge_left_deg: (out) (optional): the left eye's vergence
 * @verge_right_deg: (out) (optional): the right eye's vergence
 *
 * Returns: %TRUE when the head pose is known (%GST_HAND_POINTING_FLAG_HAS_HEAD)
 */
gboolean
gst_hand_pointing_meta_get_head_pose (const GstHandPointingMeta * meta,
    gdouble * pan_deg, gdouble * tilt_deg, gdouble * verge_left_deg, gdouble * verge_right_deg)
{
  g_return_val_if_fail (meta != NULL, FALSE);
  if (!(meta->flags & GST_HAND_POINTING_FLAG_HAS_HEAD))
    return FALSE;
  if (pan_deg)
    *pan_deg = meta->head_pan_deg;
  if (tilt_deg)
    *tilt_deg = meta->head_tilt_deg;
  if (verge_left_deg)
    *verge_left_deg = meta->head_verge_left_deg;
  if (verge_right_deg)
    *verge_right_deg = meta->head_verge_right_deg;
  return TRUE;
}

/**
 * gst_hand_pointing_meta_get_view_state:
 * @meta: a #GstHandPointingMeta
 * @view: which view
 *
 * Returns: that view's tracking state; %GST_HAND_POINTING_STATE_ACQUIRING for the right
 *   view of mono input
 */
GstHandPointingState
gst_hand_pointing_meta_get_view_state (const GstHandPointingMeta * meta, GstHandPointingView view)
{
  const GstHandPointingEye *eye;

  g_return_val_if_fail (meta != NULL, GST_HAND_POINTING_STATE_ACQUIRING);
  eye = view_eye (meta, view);
  return eye ? eye->state : GST_HAND_POINTING_STATE_ACQUIRING;
}

/**
 * gst_hand_pointing_meta_get_gesture:
 * @meta: a #GstHandPointingMeta
 * @view: which view
 *
 * Returns: what the hand does in that view; %GST_HAND_POINTING_GESTURE_UNKNOWN without key
 *   points (the motion-only detector) and for the right view of mono input
 */
GstHandPointingGesture
gst_hand_pointing_meta_get_gesture (const GstHandPointingMeta * meta, GstHandPointingView view)
{
  g_return_val_if_fail (meta != NULL, GST_HAND_POINTING_GESTURE_UNKNOWN);
  if (!view_eye (meta, view))
    return GST_HAND_POINTING_GESTURE_UNKNOWN;
  return view == GST_HAND_POINTING_VIEW_RIGHT ? meta->right_gesture : meta->left_gesture;
}

/**
 * gst_hand_pointing_meta_get_fingertip:
 * @meta: a #GstHandPointingMeta
 * @view: which view
 * @x: (out) (optional): the index fingertip in that view, pixels, right
 * @y: (out) (optional): pixels, down
 * @pointing_deg: (out) (optional): palm -> fingertip in the image, degrees, 0 = +x,
 *   counter-clockwise with y up
 *
 * Returns: %TRUE when that view tracks the hand; the outputs are left alone otherwise
 */
gboolean
gst_hand_pointing_meta_get_fingertip (const GstHandPointingMeta * meta, GstHandPointingView view,
    gdouble * x, gdouble * y, gdouble * pointing_deg)
{
  const GstHandPointingEye *eye;

  g_return_val_if_fail (meta != NULL, FALSE);
  eye = view_eye (meta, view);
  if (!eye || eye->state != GST_HAND_POINTING_STATE_TRACKING)
    return FALSE;
  if (x)
    *x = eye->fingertip_x;
  if (y)
    *y = eye->fingertip_y;
  if (pointing_deg)
    *pointing_deg = eye->pointing_deg;
  return TRUE;
}

/**
 * gst_hand_pointing_meta_get_contour:
 * @meta: a #GstHandPointingMeta
 * @view: which view
 * @n_values: (out): the number of floats returned: twice the number of points
 *
 * Returns: (array length=n_values) (transfer none): the estimated contour of that view as
 *   x0, y0, x1, y1, ... in pixels (a closed polygon), owned by the meta; empty for the
 *   right view of mono input
 */
const gfloat *
gst_hand_pointing_meta_get_contour (const GstHandPointingMeta * meta, GstHandPointingView view,
    guint * n_values)
{
  const GstHandPointingEye *eye;

  g_return_val_if_fail (meta != NULL && n_values != NULL, NULL);
  eye = view_eye (meta, view);
  *n_values = eye ? 2 * eye->n_contour_points : 0;
  return eye ? &eye->contour[0][0] : NULL;
}
