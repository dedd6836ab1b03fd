/* video: frames out of tarn as a video or a folder of PNGs (`tarn record`).
 *
 * A video is made by the ffmpeg program, fed raw RGB frames through a pipe
 * to its stdin: tarn links no codec library, and any format and codec the
 * installed ffmpeg has works (the extension of OUT picks them, as ffmpeg
 * does). When the ffmpeg program is missing the frames become PNGs instead,
 * and video_open says where and how to make the video later. */
#ifndef TARN_VIDEO_H
#define TARN_VIDEO_H

#include <stdbool.h>

typedef struct video video;

typedef struct video_desc {
    const char *out;             /* FILE.mp4 (any ffmpeg output), or DIR/ (or an existing folder): PNGs */
    int width, height;
    int fps;
    const char *ffmpeg;          /* the program to run (0: "ffmpeg" on PATH) */
} video_desc;

/* Starts the output. note gets a message for the user when the frames go
 * somewhere other than asked (ffmpeg missing), else "". NULL with the
 * reason in err when nothing can be written. */
video *video_open(const video_desc *d, char *note, int notelen, char *err, int errlen);
/* One frame: width * height * 3 bytes, RGB, the top row first. */
bool video_frame(video *v, const unsigned char *rgb, char *err, int errlen);
/* Finishes the file (waits for ffmpeg) and frees v; false with the reason
 * when ffmpeg failed or a frame could not be written before. */
bool video_close(video *v, char *err, int errlen);

/* The file or the folder (ending in '/') written. */
const char *video_where(const video *v);
bool video_is_png(const video *v);

/* Frame i's file in a PNG folder: DIR/frame-00000.png (dir ends in '/'). */
void video_png_path(const char *dir, int i, char *out, int outlen);

#endif
