"""A video of a scene: the world drawn by ``World.render`` (on the CPU, no GPU or window) every
few steps, written as an animated GIF with Pillow, or as an MP4 when the output name ends in
``.mp4`` and imageio with its ffmpeg plugin is installed (``pip install imageio[ffmpeg]``).

    python examples/video.py --scene pyramid --seconds 4 --output pyramid.gif

The camera is the default one of the first frame (``World.render_camera``), kept for the whole
video so that the view stays still while the bodies move.
"""

import argparse
import os

import rebond

SCENES = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "scenes")


def frames(scene, seconds, fps, width, height):
    """Yields ``seconds * fps`` pictures, ``uint8`` (height, width, 3), of ``scene`` (a built-in
    scene's name, or a path) from its start, one every ``1 / fps`` seconds of simulated time
    (rounded to whole steps)."""
    path = scene if os.path.exists(scene) else os.path.join(SCENES, scene + ".json")
    world = rebond.World.from_scene(path)
    steps_per_frame = max(1, round(1 / (fps * world.timestep)))
    camera = world.render_camera(width, height)
    for _ in range(round(seconds * fps)):
        yield world.render(width, height, camera)
        world.step(steps_per_frame)


def write_video(pictures, output, fps):
    """Writes the pictures to ``output``: an MP4 through imageio for ``.mp4``, else a looping GIF
    through Pillow. Returns the number of frames written."""
    pictures = list(pictures)
    if output.endswith(".mp4"):
        import imageio.v2 as imageio

        imageio.mimwrite(output, pictures, fps=fps)
        return len(pictures)
    from PIL import Image

    images = [Image.fromarray(picture) for picture in pictures]
    # GIF frame durations are whole hundredths of a second.
    duration = 10 * round(100 / fps)
    images[0].save(output, save_all=True, append_images=images[1:], duration=duration, loop=0)
    return len(images)


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--scene", default="pyramid", help="a built-in scene's name or a path")
    parser.add_argument("--seconds", type=float, default=3.0, help="simulated seconds")
    parser.add_argument("--fps", type=float, default=20.0, help="frames per simulated second")
    parser.add_argument("--width", type=int, default=320)
    parser.add_argument("--height", type=int, default=240)
    parser.add_argument("--output", default="video.gif", help=".gif, or .mp4 with imageio")
    args = parser.parse_args(argv)
    count = write_video(
        frames(args.scene, args.seconds, args.fps, args.width, args.height), args.output, args.fps
    )
    print(f"{args.output}: {count} frames of {args.width} x {args.height}")
    return count


if __name__ == "__main__":
    main()
