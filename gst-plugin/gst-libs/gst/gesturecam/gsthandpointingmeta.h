/* GstHandPointingMeta: where a tracked hand is and where it points, attached by the
 * gesturecam handtracker element to every buffer it outputs.
 *
 * Link with gstgesturecammeta-1.0 (pkg-config gstreamer-gesturecam-meta-1.0).
 * Units and frames are documented in docs/metadata.md. */
#ifndef GST_HAND_POINTING_META_H
#define GST_HAND_POINTING_META_H

#include <gst/gst.h>

G_BEGIN_DECLS

#ifndef GST_GESTURECAM_META_API
# if defined(_WIN32)
#  define GST_GESTURECAM_META_API __declspec(dllimport) extern
# else
#  define GST_GESTURECAM_META_API extern
# endif
#endif

/* At most this many contour points are stored per eye; longer contours are subsampled
 * evenly along the polygon. */
#define GST_HAND_POINTING_MAX_CONTOUR_POINTS 256

typedef enum {
  GST_HAND_POINTING_STATE_ACQUIRING = 0,
  GST_HAND_POINTING_STATE_TRACKING = 1,
  GST_HAND_POINTING_STATE_LOST = 2,
} GstHandPointingState;

/* What the hand does, from its key points (the learned detector); UNKNOWN without them
 * (the motion-only detector, which assumes a pointing hand). */
typedef enum {
  GST_HAND_POINTING_GESTURE_UNKNOWN = 0,
  GST_HAND_POINTING_GESTURE_POINTING = 1,
  GST_HAND_POINTING_GESTURE_OPEN = 2,
  GST_HAND_POINTING_GESTURE_FIST = 3,
  GST_HAND_POINTING_GESTURE_OTHER = 4,
} GstHandPointingGesture;

typedef enum {
  GST_HAND_POINTING_FLAG_NONE = 0,
  /* Both views were tracked (otherwise only the left one: mono input). */
  GST_HAND_POINTING_FLAG_STEREO = (1 << 0),
  /* The 3D fields (fingertip_mm ... elevation_deg) are valid. */
  GST_HAND_POINTING_FLAG_HAS_3D = (1 << 1),
  /* The head_* fields are valid: the head pose at capture is known. */
  GST_HAND_POINTING_FLAG_HAS_HEAD = (1 << 2),
  /* One view had no frame for this output time (late or ended stream): the tracker was
   * not run and the fields repeat the most recent result. */
  GST_HAND_POINTING_FLAG_INCOMPLETE = (1 << 3),
  /* The buffer shows a whole input view (output left or right), so the 2D fields are in
   * the buffer's own pixels; scale transforms rescale them. */
  GST_HAND_POINTING_FLAG_FULL_VIEW = (1 << 4),
} GstHandPointingFlags;

/* Which view's estimate an accessor reads. */
typedef enum {
  GST_HAND_POINTING_VIEW_LEFT = 0,
  GST_HAND_POINTING_VIEW_RIGHT = 1,
} GstHandPointingView;

/* One view's estimate, in that camera's image pixels (x right, y down, origin at the
 * top-left corner of the input frame). C code reads the fields; bindings (GObject
 * introspection) see an opaque record and read them through the accessors below, so new
 * fields never change what a binding sees. */
typedef struct {
  /*< private >*/
  GstHandPointingState state;
  gdouble x, y;            /* palm centre: the template origin of the state vector */
  gdouble rotation_deg;    /* in-plane rotation of the state, clockwise on screen */
  gdouble scale;           /* relative to the template captured at acquisition */
  gdouble confidence;      /* 0..1 */
  gint bbox_x, bbox_y, bbox_width, bbox_height;   /* of the estimated contour */
  gdouble fingertip_x, fingertip_y;               /* index fingertip */
  gdouble pointing_deg;    /* palm -> fingertip, 0 = +x, counter-clockwise, y up */
  guint n_contour_points;
  gfloat contour[GST_HAND_POINTING_MAX_CONTOUR_POINTS][2];  /* closed polygon, (x, y) */
} GstHandPointingEye;

typedef struct {
  GstMeta meta;

  /*< private >*/

  guint64 frame;                 /* index of the stereo pair since the tracker started */
  GstHandPointingState state;    /* tracking only when every tracked view tracks */
  guint flags;                   /* GstHandPointingFlags */
  GstHandPointingEye left;
  GstHandPointingEye right;      /* valid with GST_HAND_POINTING_FLAG_STEREO */

  /* 3D, left camera frame at capture (x right, y down, z forward), millimetres;
   * valid with GST_HAND_POINTING_FLAG_HAS_3D. */
  gdouble fingertip_mm[3];
  gdouble palm_mm[3];
  gdouble direction[3];          /* unit vector, palm -> fingertip */
  gdouble azimuth_deg;           /* atan2(dx, dz): positive to the right */
  gdouble elevation_deg;         /* atan2(-dy, hypot(dx, dz)): positive up */

  /* Head pose at capture, degrees; valid with GST_HAND_POINTING_FLAG_HAS_HEAD. */
  gdouble head_pan_deg, head_tilt_deg, head_verge_left_deg, head_verge_right_deg;

  /* The rectangle of the input view shown in this buffer, in input pixels: the whole
   * frame with GST_HAND_POINTING_FLAG_FULL_VIEW, else the attended crop of the left view.
   * Scale transforms rescale it, and every 2D field, only with FULL_VIEW. */
  gint view_x, view_y, view_width, view_height;

  /* Each view's gesture (right: with GST_HAND_POINTING_FLAG_STEREO). The 3D fields are
   * set only on frames where the hand points. */
  GstHandPointingGesture left_gesture, right_gesture;
} GstHandPointingMeta;

GST_GESTURECAM_META_API
GType gst_hand_pointing_meta_api_get_type (void);
#define GST_HAND_POINTING_META_API_TYPE (gst_hand_pointing_meta_api_get_type ())

GST_GESTURECAM_META_API
const GstMetaInfo *gst_hand_pointing_meta_get_info (void);
#define GST_HAND_POINTING_META_INFO (gst_hand_pointing_meta_get_info ())

#define gst_buffer_get_hand_pointing_meta(b) \
  ((GstHandPointingMeta *) gst_buffer_get_meta ((b), GST_HAND_POINTING_META_API_TYPE))

/* Adds a zeroed meta (state ACQUIRING, scale 1) to a writable buffer. */
GST_GESTURECAM_META_API
GstHandPointingMeta *gst_buffer_add_hand_pointing_meta (GstBuffer * buffer);

/* Stores a contour of n (x, y) points into eye, subsampling evenly when n exceeds
 * GST_HAND_POINTING_MAX_CONTOUR_POINTS. */
GST_GESTURECAM_META_API
void gst_hand_pointing_eye_set_contour (GstHandPointingEye * eye, const gfloat * xy,
    guint n);

GST_GESTURECAM_META_API
const gchar *gst_hand_pointing_state_to_string (GstHandPointingState state);

/* Accessors for bindings (and C): documented in gsthandpointingaccess.c. */
GST_GESTURECAM_META_API
GstHandPointingMeta *gst_hand_pointing_meta_from_buffer (GstBuffer * buffer);

GST_GESTURECAM_META_API
guint64 gst_hand_pointing_meta_get_frame (const GstHandPointingMeta * meta);

GST_GESTURECAM_META_API
GstHandPointingState gst_hand_pointing_meta_get_state (const GstHandPointingMeta * meta);

GST_GESTURECAM_META_API
GstHandPointingFlags gst_hand_pointing_meta_get_flags (const GstHandPointingMeta * meta);

GST_GESTURECAM_META_API
gboolean gst_hand_pointing_meta_get_direction (const GstHandPointingMeta * meta,
    gdouble * azimuth_deg, gdouble * elevation_deg);

GST_GESTURECAM_META_API
gboolean gst_hand_pointing_meta_get_fingertip_mm (const GstHandPointingMeta * meta,
    gdouble * x, gdouble * y, gdouble * z);

GST_GESTURECAM_META_API
gboolean gst_hand_pointing_meta_get_head_pose (const GstHandPointingMeta * meta,
    gdouble * pan_deg, gdouble * tilt_deg, gdouble * verge_left_deg, gdouble * verge_right_deg);

GST_GESTURECAM_META_API
GstHandPointingState gst_hand_pointing_meta_get_view_state (const GstHandPointingMeta * meta,
    GstHandPointingView view);

GST_GESTURECAM_META_API
GstHandPointingGesture gst_hand_pointing_meta_get_gesture (const GstHandPointingMeta * meta,
    GstHandPointingView view);

GST_GESTURECAM_META_API
gboolean gst_hand_pointing_meta_get_fingertip (const GstHandPointingMeta * meta,
    GstHandPointingView view, gdouble * x, gdouble * y, gdouble * pointing_deg);

GST_GESTURECAM_META_API
const gfloat *gst_hand_pointing_meta_get_contour (const GstHandPointingMeta * meta,
    GstHandPointingView view, guint * n_values);

G_END_DECLS

/* GTypes of the enums above (GST_TYPE_HAND_POINTING_GESTURE, ...), generated by glib-mkenums. */
#include <gst/gesturecam/gsthandpointing-enumtypes.h>

#endif /* GST_HAND_POINTING_META_H */
