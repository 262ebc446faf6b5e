"""Options shared by the commands: the outputs (--archive, --vtu, --xdmf, --images) and
argument types that refuse bad values with a message naming the option (exit 2)."""

import argparse
import sys

MAX_IMAGE_SIDE = 8192      # pixels: an off-screen render buffer of 8192^2 RGBA is 256 MB


def count_type(minimum=1):
    """An argparse type: a whole number >= minimum."""
    def parse(text):
        try:
            v = int(text)
        except ValueError:
            raise argparse.ArgumentTypeError(f"{text!r} is not a whole number") from None
        if v < minimum:
            raise argparse.ArgumentTypeError(f"must be at least {minimum} (found {v})")
        return v
    parse.__name__ = "count"
    return parse


def seconds_type(text):
    import math
    try:
        v = float(text)
    except ValueError:
        v = math.nan
    if not 0 < v < 1e6:
        raise argparse.ArgumentTypeError(f"{text!r}: give a time in seconds, > 0")
    return v


def add_member_force_arguments(p, modes=False):
    """--member-forces (and for modes --member-forces-scale): section forces and stresses
    at the members' ends in --json (docs/structure.md, "Member forces")."""
    p.add_argument("--member-forces", action="store_true", help="add the members' end "
                   "forces and extreme-fibre stresses to --json and --archive" + (
                       " (per mode)" if modes else " (envelope over the output times)"))
    if modes:
        def amplitude(text):
            try:
                v = float(text)
            except ValueError:
                v = float("nan")
            if not 0 < v < 1e6:
                raise argparse.ArgumentTypeError(f"{text!r}: give an amplitude in m, > 0")
            return v
        p.add_argument("--member-forces-scale", type=amplitude, default=None, metavar="M",
                       help="scale each mode so its largest node translation is M metres "
                       "(default: mass-normalised modes)")


def add_output_arguments(p):
    g = p.add_argument_group("outputs")
    g.add_argument("--archive", metavar="OUT.h5", help="write an HDF5 result archive")
    g.add_argument("--vtu", metavar="OUT.vtu", help="write a ParaView VTU file")
    g.add_argument("--xdmf", metavar="OUT.xdmf", help="write an XDMF series (one step per "
                   "mode)")
    g.add_argument("--images", metavar="DIR", help="render one PNG per mode (off-screen)")
    g.add_argument("--animate", nargs="?", const="gif", choices=("gif", "mp4"),
                   help="with --images: an animation per mode, GIF (default) or MP4 "
                   "(needs imageio-ffmpeg)")
    g.add_argument("--view", choices=("iso", "xy", "xz", "yz"),
                   help="with --images: the direction of view (default: xz for a plane "
                   "model, else iso)")
    g.add_argument("--image-size", metavar="WxH", default="1024x768",
                   help=f"image size in pixels (default 1024x768, at most "
                   f"{MAX_IMAGE_SIDE} a side)")


def _size(text):
    from ..errors import ModelError
    try:
        w, h = (int(v) for v in text.lower().split("x"))
        if not (16 <= w <= MAX_IMAGE_SIDE and 16 <= h <= MAX_IMAGE_SIDE):
            raise ValueError
    except ValueError:
        raise ModelError(f"give WIDTHxHEIGHT in pixels, each 16..{MAX_IMAGE_SIDE}, e.g. "
                         "1024x768", None, f"--image-size {text!r}") from None
    return w, h


FILE_OPTIONS = ("archive", "vtu", "xdmf", "csv")
FOLDER_OPTIONS = ("images", "plots")


def check_outputs(args, model=None):
    """Check every output option of `args` against each other and against the files
    this run read (`cranefe.outpaths.Plan`), before anything is computed."""
    import os

    from ..outpaths import Plan, files_read
    inputs = [("the model or scene", args.file)] if getattr(args, "file", None) else []
    if model is not None:
        inputs.append(("the model", model.file))
        if model.scene_file:
            inputs.append(("the scene", model.scene_file))
    inputs += [("a file", p) for p in files_read()]
    plan = Plan(inputs)
    for name in FILE_OPTIONS:
        path = getattr(args, name, None)
        companions = ()
        if name == "xdmf" and path:        # its heavy data: BASE.xdmf.h5 beside it
            companions = (os.path.splitext(path)[0] + ".xdmf.h5",)
        plan.file(f"--{name}", path, companions)
    for name in FOLDER_OPTIONS:
        plan.folder(f"--{name}", getattr(args, name, None))
    if getattr(args, "image_size", None) is not None:
        _size(args.image_size)
    animate = getattr(args, "animate", None)
    if animate and hasattr(args, "images"):        # modes, damping: a format of --images
        if not args.images:
            from ..errors import ModelError
            raise ModelError("--animate needs --images DIR")
        if animate == "mp4":
            from ..outputs.render import _need_ffmpeg
            _need_ffmpeg()
    elif animate:                                   # simulate: a file
        _animation_file(plan, animate)
    return plan


def _animation_file(plan, path):
    import os

    from ..errors import ModelError
    if os.path.splitext(path)[1].lower() not in (".gif", ".mp4"):
        raise ModelError("give a file name ending in .gif or .mp4", None,
                         f"--animate {path!r}")
    plan.file("--animate", path)
    if path.lower().endswith(".mp4"):
        from ..outputs.render import _need_ffmpeg
        _need_ffmpeg()


def add_animation_arguments(p):
    """simulate: --animate FILE.gif|FILE.mp4 with --view and --image-size."""
    p.add_argument("--animate", metavar="OUT.gif", help="an operation scene: the crane "
                   "moving, with the loads' trails (GIF, or MP4 for a name ending in "
                   ".mp4, which needs imageio-ffmpeg)")
    p.add_argument("--view", choices=("iso", "xy", "xz", "yz"),
                   help="with --animate: the direction of view (default: xz for a plane "
                   "model, else iso)")
    p.add_argument("--image-size", metavar="WxH", default="1024x768",
                   help="with --animate: frame size in pixels (default 1024x768)")


def image_size(args):
    return _size(args.image_size)


def write_outputs(args, model, system, results, modal, member_forces=None,
                  colour_forces=None):
    """Write what the options ask for; report each path on stderr. `member_forces`
    (`cranefe.outputs.member_forces.MemberForces` of the modes) adds cell data to --vtu
    and --xdmf; `colour_forces` (the same kind) colours the members of --images by
    their stress."""
    written = []
    check_outputs(args, model)
    if args.archive is not None:
        from ..outputs import archive
        written.append(archive.write(args.archive, model, system, results,
                                     command=["cranefe"] + args.argv,
                                     timings=modal.timings))
    if args.vtu is not None:
        from ..outputs.paraview import write_vtu
        written.append(write_vtu(args.vtu, model, system.dofs, modal,
                                 member_forces=member_forces))
    if args.xdmf is not None:
        from ..outputs.paraview import write_xdmf_modes
        written.append(write_xdmf_modes(args.xdmf, model, system.dofs, modal,
                                        member_forces=member_forces))
    if args.images is not None:
        from ..outputs.render import render_modes
        written += render_modes(args.images, model, system.dofs, modal,
                                size=_size(args.image_size), animate=args.animate,
                                view=args.view, member_forces=colour_forces)
    for path in written:
        print(f"wrote {path}", file=sys.stderr)
    return written
