#include "render/video_encoder.h"

extern "C" {
#include <libavcodec/avcodec.h>
#include <libavformat/avformat.h>
#include <libavutil/imgutils.h>
#include <libavutil/opt.h>
#include <libswscale/swscale.h>
}

#include <cmath>
#include <cstdio>
#include <filesystem>

#include "pronk/error.h"
#include "pronk/file_io.h"

namespace pronk::render {
namespace {

std::string avError(int code) {
  char text[AV_ERROR_MAX_STRING_SIZE] = {0};
  av_strerror(code, text, sizeof text);
  return text;
}

}  // namespace

struct VideoEncoder::Impl {
  std::string path;     // the video, once whole
  std::string partial;  // PATH.partial, written until then
  int width = 0, height = 0;
  AVFormatContext* format = nullptr;
  AVCodecContext* codec = nullptr;
  AVStream* stream = nullptr;
  AVFrame* frame = nullptr;
  AVPacket* packet = nullptr;
  SwsContext* sws = nullptr;
  bool finished = false;

  void drain(bool flush) {
    if (flush) avcodec_send_frame(codec, nullptr);
    while (true) {
      const int r = avcodec_receive_packet(codec, packet);
      if (r == AVERROR(EAGAIN) || r == AVERROR_EOF) return;
      if (r < 0) throw Error(path + ": encoding failed: " + avError(r));
      av_packet_rescale_ts(packet, codec->time_base, stream->time_base);
      packet->stream_index = stream->index;
      const int w = av_interleaved_write_frame(format, packet);
      if (w < 0) throw Error(path + ": writing failed: " + avError(w));
    }
  }

  void release() {
    if (sws) sws_freeContext(sws);
    if (packet) av_packet_free(&packet);
    if (frame) av_frame_free(&frame);
    if (codec) avcodec_free_context(&codec);
    if (format) {
      if (format->pb) avio_closep(&format->pb);
      avformat_free_context(format);
    }
    sws = nullptr;
    format = nullptr;
  }
};

VideoEncoder::VideoEncoder(const std::string& path, int width, int height, double fps) : impl_(std::make_unique<Impl>()) {
  av_log_set_level(AV_LOG_ERROR);  // x264 prints its statistics otherwise
  Impl& v = *impl_;
  v.path = path;
  v.partial = path + ".partial";
  v.width = width;
  v.height = height;
  if (width <= 0 || height <= 0 || width % 2 || height % 2) {
    throw Error(path + ": video size " + std::to_string(width) + "x" + std::to_string(height) +
                " must be positive and even (H.264 4:2:0)");
  }
  if (!(fps > 0) || !std::isfinite(fps) || fps > 1000) {
    throw Error(path + ": video frame rate " + std::to_string(fps) + " must be in (0, 1000]");
  }
  checkReplaceable(path, "video");
  checkReplaceable(v.partial, "video");
  try {
    if (avformat_alloc_output_context2(&v.format, nullptr, "mp4", path.c_str()) < 0 || !v.format) {
      throw Error(path + ": cannot create an MP4 container");
    }
    const AVCodec* codec = avcodec_find_encoder_by_name("libx264");
    if (!codec) codec = avcodec_find_encoder(AV_CODEC_ID_H264);
    if (!codec) throw Error(path + ": no H.264 encoder in this FFmpeg build");
    v.stream = avformat_new_stream(v.format, nullptr);
    v.codec = avcodec_alloc_context3(codec);
    v.codec->width = width;
    v.codec->height = height;
    const AVRational rate = av_d2q(fps, 100000);
    v.codec->time_base = av_inv_q(rate);
    v.codec->framerate = rate;
    v.codec->pix_fmt = AV_PIX_FMT_YUV420P;
    v.codec->gop_size = 60;
    v.codec->thread_count = 0;  // one encoder thread halves the throughput
    if (v.format->oformat->flags & AVFMT_GLOBALHEADER) v.codec->flags |= AV_CODEC_FLAG_GLOBAL_HEADER;
    av_opt_set(v.codec->priv_data, "preset", "veryfast", 0);
    av_opt_set(v.codec->priv_data, "crf", "23", 0);
    int r = avcodec_open2(v.codec, codec, nullptr);
    if (r < 0) throw Error(path + ": cannot open the H.264 encoder: " + avError(r));
    avcodec_parameters_from_context(v.stream->codecpar, v.codec);
    v.stream->time_base = v.codec->time_base;
    r = avio_open(&v.format->pb, v.partial.c_str(), AVIO_FLAG_WRITE);
    if (r < 0) throw Error(path + ": cannot open for writing: " + avError(r));
    r = avformat_write_header(v.format, nullptr);
    if (r < 0) throw Error(path + ": cannot write the MP4 header: " + avError(r));
    v.frame = av_frame_alloc();
    v.frame->format = AV_PIX_FMT_YUV420P;
    v.frame->width = width;
    v.frame->height = height;
    if (av_frame_get_buffer(v.frame, 0) < 0) throw Error(path + ": out of memory for a frame");
    v.packet = av_packet_alloc();
    v.sws = sws_getContext(width, height, AV_PIX_FMT_RGBA, width, height, AV_PIX_FMT_YUV420P, SWS_BILINEAR, nullptr,
                           nullptr, nullptr);
    if (!v.sws) throw Error(path + ": cannot set up the colour conversion");
  } catch (...) {
    v.release();
    std::remove(v.partial.c_str());
    throw;
  }
}

VideoEncoder::~VideoEncoder() {
  impl_->release();
  if (!impl_->finished) std::remove(impl_->partial.c_str());  // never finished: no video
}

void VideoEncoder::addFrame(const std::vector<uint8_t>& rgba) {
  Impl& v = *impl_;
  if (rgba.size() != size_t(v.width) * v.height * 4) throw Error(v.path + ": frame of the wrong size");
  if (av_frame_make_writable(v.frame) < 0) throw Error(v.path + ": frame not writable");
  const uint8_t* source[1] = {rgba.data()};
  const int stride[1] = {v.width * 4};
  sws_scale(v.sws, source, stride, 0, v.height, v.frame->data, v.frame->linesize);
  v.frame->pts = frames_++;
  const int r = avcodec_send_frame(v.codec, v.frame);
  if (r < 0) throw Error(v.path + ": encoding failed: " + avError(r));
  v.drain(false);
}

void VideoEncoder::finish() {
  Impl& v = *impl_;
  if (v.finished || !v.format) return;
  std::string failure;
  try {
    v.drain(true);
  } catch (const Error& e) {
    failure = e.what();
  }
  if (failure.empty()) {
    if (const int r = av_write_trailer(v.format); r < 0) failure = v.path + ": writing the MP4 trailer failed: " + avError(r);
  }
  if (failure.empty() && v.format->pb) {
    // Buffered writes fail late (a full disk, a file-size limit): their error stays on the stream.
    avio_flush(v.format->pb);
    const int error = v.format->pb->error;
    const int closed = avio_closep(&v.format->pb);
    if (error < 0 || closed < 0) failure = v.path + ": writing the video failed: " + avError(error < 0 ? error : closed);
  }
  std::error_code ec;
  if (failure.empty()) {
    std::filesystem::rename(v.partial, v.path, ec);
    if (ec) failure = v.path + ": cannot replace the video: " + ec.message();
  }
  if (!failure.empty()) {
    v.release();
    std::filesystem::remove(v.partial, ec);
    throw Error(failure + " (no video written)");
  }
  v.finished = true;
}

void writePng(const std::string& path, const std::vector<uint8_t>& rgba, int width, int height) {
  const AVCodec* codec = avcodec_find_encoder(AV_CODEC_ID_PNG);
  if (!codec) throw Error(path + ": no PNG encoder in this FFmpeg build");
  AVCodecContext* context = avcodec_alloc_context3(codec);
  AVFrame* frame = av_frame_alloc();
  AVPacket* packet = av_packet_alloc();
  std::string failure;
  context->width = width;
  context->height = height;
  context->pix_fmt = AV_PIX_FMT_RGBA;
  context->time_base = AVRational{1, 1};
  if (avcodec_open2(context, codec, nullptr) < 0) {
    failure = "cannot open the PNG encoder";
  } else {
    frame->format = AV_PIX_FMT_RGBA;
    frame->width = width;
    frame->height = height;
    frame->data[0] = const_cast<uint8_t*>(rgba.data());
    frame->linesize[0] = width * 4;
    if (avcodec_send_frame(context, frame) < 0 || avcodec_receive_packet(context, packet) < 0) {
      failure = "PNG encoding failed";
    } else {
      try {
        replaceFileAtomically(path, std::string(reinterpret_cast<const char*>(packet->data), size_t(packet->size)),
                              "still");
      } catch (const Error& e) {
        failure = e.what();
      }
    }
  }
  av_packet_free(&packet);
  av_frame_free(&frame);
  avcodec_free_context(&context);
  if (!failure.empty()) throw Error(path + ": " + failure);
}

VideoInfo probeVideo(const std::string& path) {
  AVFormatContext* format = nullptr;
  if (avformat_open_input(&format, path.c_str(), nullptr, nullptr) < 0) throw Error(path + ": cannot open the video");
  VideoInfo info;
  if (avformat_find_stream_info(format, nullptr) >= 0) {
    for (unsigned i = 0; i < format->nb_streams; ++i) {
      const AVStream* s = format->streams[i];
      if (s->codecpar->codec_type != AVMEDIA_TYPE_VIDEO) continue;
      info.codec = avcodec_get_name(s->codecpar->codec_id);
      info.width = s->codecpar->width;
      info.height = s->codecpar->height;
      info.frames = long(s->nb_frames);
      if (s->duration != AV_NOPTS_VALUE) info.duration_s = s->duration * av_q2d(s->time_base);
      break;
    }
  }
  avformat_close_input(&format);
  return info;
}

}  // namespace pronk::render
